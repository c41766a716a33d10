// Tet kernels: the Y3D law against Hooke's law, rigid motion, its own energy, the scalar reference, and the
// stable step against exact geometry. Every check runs on both tet_forces_scalar and tet_forces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include "kernels/stable_step.hpp"
#include "kernels/tet_forces.hpp"

namespace rift::kernels {
namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;
using ForceFn = TetForceStatus (*)(const TetForceArgs&, size_t, size_t);

// Limestone of femdem.md 1e: E = 40 GPa, nu = 0.25 -> lambda = mu = 16 GPa.
constexpr double kE = 40e9;
constexpr TetMaterial kRock{16e9, 16e9, 0.0};

// A tet mesh with everything tet_forces needs, built from reference positions.
struct Mesh {
  std::vector<double> x0, x, v;
  std::vector<int32_t> tets, material;
  std::vector<TetMaterial> materials{kRock};
  std::vector<double> dm_inv, volume0, force, stress, energy;

  size_t num_tets() const { return tets.size() / 4; }
  size_t prepare() {
    dm_inv.assign(9 * num_tets(), 0.0);
    volume0.assign(num_tets(), 0.0);
    material.resize(num_tets(), 0);
    force.assign(12 * num_tets(), -1.0);
    stress.assign(6 * num_tets(), -1.0);
    energy.assign(num_tets(), -1.0);
    if (x.empty()) x = x0;
    v.resize(x0.size(), 0.0);
    return tet_prepare(x0, tets, dm_inv, volume0, 0, num_tets());
  }
  TetForceArgs args() { return {x, v, tets, dm_inv, volume0, material, materials, force, stress, energy}; }
  TetForceStatus run(ForceFn fn) { return fn(args(), 0, num_tets()); }
  // x = A X + b for every node.
  void map(const Mat3& A, const std::array<double, 3>& b) {
    x.resize(x0.size());
    for (size_t n = 0; n < x0.size() / 3; ++n)
      for (int i = 0; i < 3; ++i)
        x[3 * n + i] = A[i][0] * x0[3 * n] + A[i][1] * x0[3 * n + 1] + A[i][2] * x0[3 * n + 2] + b[i];
  }
};

// A general (no two edges equal, no right angles) positively oriented tet.
Mesh general_tet() {
  Mesh m;
  m.x0 = {0.1, -0.2, 0.05, 1.3, 0.1, -0.1, 0.2, 0.9, 0.3, -0.15, 0.25, 1.1};
  m.tets = {0, 1, 2, 3};
  return m;
}

// 2 x 2 x 2 cubes of side h, 6 Kuhn tets each (48 tets, 27 nodes, node 13 interior), every node moved by up
// to +-10 % of h so no tet is regular or axis-aligned.
Mesh cube_patch() {
  Mesh m;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        m.x0.push_back(i + jitter(rng));
        m.x0.push_back(j + jitter(rng));
        m.x0.push_back(k + jitter(rng));
      }
  auto node = [](int i, int j, int k) { return static_cast<int32_t>(i + 3 * j + 9 * k); };
  static constexpr int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int32_t, 4> t;
          t[0] = node(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = node(c[0], c[1], c[2]);
          }
          // Odd permutations of the axes give negatively oriented tets: swap two corners.
          const bool odd = (p[0] > p[1]) + (p[0] > p[2]) + (p[1] > p[2]) == 1 ||
                           (p[0] > p[1]) + (p[0] > p[2]) + (p[1] > p[2]) == 3;
          if (odd) std::swap(t[2], t[3]);
          m.tets.insert(m.tets.end(), t.begin(), t.end());
        }
  return m;
}

Mat3 identity_plus(const Mat3& eps) {
  Mat3 A = eps;
  for (int i = 0; i < 3; ++i) A[i][i] += 1.0;
  return A;
}

double norm6(const double* s) {  // Frobenius norm of a symmetric tensor in Voigt order
  return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

// Runs a test on the scalar reference and on the vector path (named, so CTest names carry no addresses).
enum class Path { scalar, vector };
void PrintTo(Path p, std::ostream* os) {
  *os << (p == Path::scalar ? "scalar" : "vector");
}
class BothPaths : public ::testing::TestWithParam<Path> {
 protected:
  static ForceFn kernel() { return GetParam() == Path::scalar ? &tet_forces_scalar : &tet_forces; }
};
INSTANTIATE_TEST_SUITE_P(TetForces, BothPaths, ::testing::Values(Path::scalar, Path::vector),
                         [](const auto& info) { return info.param == Path::scalar ? "scalar" : "vector"; });

// 1a. Uniform strain 1e-7 on a general tet reproduces Hooke's law. The law differs from Hooke by terms
// quadratic in eps, i.e. 1e-7 relative here; 1e-6 leaves a factor 10 and would catch any O(1) slip
// (a missing factor 1/2 on lambda, a transposed Dm^-1, ...).
TEST_P(BothPaths, PatchTestHookeAtSmallStrain) {
  Mesh m = general_tet();
  ASSERT_EQ(m.prepare(), 0u);
  const Mat3 eps = {{{1.0e-7, 0.3e-7, -0.2e-7}, {0.3e-7, -0.5e-7, 0.4e-7}, {-0.2e-7, 0.4e-7, 0.8e-7}}};
  m.map(identity_plus(eps), {0.5, -0.25, 2.0});
  EXPECT_EQ(m.run(kernel()).inverted, 0u);
  const double tr = eps[0][0] + eps[1][1] + eps[2][2];
  const double lambda = kRock.lambda, mu = kRock.mu;
  const double hooke[6] = {lambda * tr + 2 * mu * eps[0][0],
                           lambda * tr + 2 * mu * eps[1][1],
                           lambda * tr + 2 * mu * eps[2][2],
                           2 * mu * eps[0][1],
                           2 * mu * eps[1][2],
                           2 * mu * eps[2][0]};
  double diff[6];
  for (int n = 0; n < 6; ++n) diff[n] = m.stress[n] - hooke[n];
  EXPECT_LT(norm6(diff), 1e-6 * norm6(hooke));
  // The four corner forces of one tet balance (to roundoff of the largest one).
  for (int i = 0; i < 3; ++i) {
    const double sum = m.force[i] + m.force[3 + i] + m.force[6 + i] + m.force[9 + i];
    EXPECT_LT(std::fabs(sum), 1e-14 * std::fabs(m.force[3 + i]) + 1e-300);
  }
}

// 1b. Any uniform F gives uniform stress, so the forces of the tets around an interior node cancel exactly
// (discrete div sigma = 0). Checked at the strain of 1a and at 2 %. Tolerance: the current coordinates (~1)
// are rounded to ~2e-16, so each tet's displacement gradient carries ~1e-15 absolute noise, i.e. 1e-15/scale
// relative to the strain, and ~24 tets meet at the node: 1e-14/scale of the largest corner force
// (1e-7 at strain 1e-7, 5e-13 at 2 %).
TEST_P(BothPaths, PatchOfTetsInteriorNodeForcesCancel) {
  for (double scale : {1e-7, 2e-2}) {
    Mesh m = cube_patch();
    ASSERT_EQ(m.prepare(), 0u);
    const Mat3 eps = {{{1.0, 0.3, -0.2}, {0.7, -0.5, 0.4}, {-0.6, 0.1, 0.8}}};
    Mat3 A;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) A[i][k] = (i == k) + scale * eps[i][k];
    m.map(A, {0.0, 0.0, 0.0});
    EXPECT_EQ(m.run(kernel()).inverted, 0u);
    std::vector<double> node_force(m.x0.size(), 0.0);
    double largest = 0.0;
    for (size_t t = 0; t < m.num_tets(); ++t)
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) {
          const double f = m.force[12 * t + 3 * a + i];
          node_force[3 * m.tets[4 * t + a] + i] += f;
          largest = std::max(largest, std::fabs(f));
        }
    ASSERT_GT(largest, 0.0);
    for (int i = 0; i < 3; ++i)
      EXPECT_LT(std::fabs(node_force[3 * 13 + i]), 1e-14 / scale * largest) << "scale " << scale;
  }
}

// 2. A 90-degree rotation (exact matrix entries) plus a translation: B = I and J = 1, so the stress is zero
// up to roundoff of the node coordinates (~1e-16 of E); 1e-9 E is the bound asked for.
TEST_P(BothPaths, RigidRotationGivesNoStress) {
  Mesh m = general_tet();
  ASSERT_EQ(m.prepare(), 0u);
  const Mat3 R = {{{0.0, -1.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}};
  m.map(R, {3.0, -1.0, 0.5});
  EXPECT_EQ(m.run(kernel()).inverted, 0u);
  EXPECT_LT(norm6(m.stress.data()), 1e-9 * kE);
  for (double f : m.force) EXPECT_LT(std::fabs(f), 1e-9 * kE);
  EXPECT_LT(std::fabs(m.energy[0]), 1e-9 * kE * m.volume0[0]);
}

// 3. Forces are minus the gradient of the stored energy (eta = 0). Central differences with step 1e-6 of
// the tet size: truncation ~(1e-6)^2 relative, roundoff ~1e-16 / 1e-6 relative, so 1e-6 is a fair bound.
// Two states: 5 % strain (|J - 1| > 0.01, the log1p branch) and 0.1 % (the series branch).
TEST_P(BothPaths, ForcesAreMinusEnergyGradient) {
  for (double scale : {5e-2, 1e-3}) {
    Mesh m = general_tet();
    ASSERT_EQ(m.prepare(), 0u);
    const Mat3 g = {{{0.9, 0.4, -0.3}, {-0.2, 0.5, 0.7}, {0.35, -0.6, 1.0}}};
    Mat3 A;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) A[i][k] = (i == k) + scale * g[i][k];
    m.map(A, {0.1, 0.2, 0.3});
    m.run(kernel());
    const std::vector<double> force = m.force;
    const double fmax = std::fabs(*std::max_element(
        force.begin(), force.end(), [](double a, double b) { return std::fabs(a) < std::fabs(b); }));
    const double h = 1e-6;  // tet size is ~1
    for (size_t c = 0; c < 12; ++c) {
      const double keep = m.x[c];
      m.x[c] = keep + h;
      m.run(kernel());
      const double e_plus = m.energy[0];
      m.x[c] = keep - h;
      m.run(kernel());
      const double e_minus = m.energy[0];
      m.x[c] = keep;
      const double gradient = (e_plus - e_minus) / (2 * h);
      EXPECT_NEAR(-gradient, force[c], 1e-6 * fmax) << "component " << c << ", strain scale " << scale;
    }
  }
}

// 5. Inverted and flat tets are counted, the first index is absolute, their outputs are 0, and every output
// stays finite. A tet with volume0 = 0 (rejected by tet_prepare) is zeroed but not counted.
TEST_P(BothPaths, InvertedTetsReported) {
  Mesh m;
  const double base[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int t = 0; t < 11; ++t) {
    for (int n = 0; n < 12; ++n) m.x0.push_back(base[n] + 2.0 * t * (n % 3 == 0));
    for (int a = 0; a < 4; ++a) m.tets.push_back(4 * t + a);
  }
  m.x0[3 * (4 * 9 + 3) + 2] = 0.0;  // tet 9 is flat in the reference: rejected by tet_prepare
  ASSERT_EQ(m.prepare(), 1u);
  m.x = m.x0;
  for (int t : {5, 6, 10}) m.x[3 * (4 * t + 3) + 2] = -0.5;  // node 3 through the opposite face
  m.x[3 * (4 * 8 + 3) + 2] = 0.0;                            // tet 8 flattened: J = 0
  const TetForceStatus all = m.run(kernel());
  EXPECT_EQ(all.inverted, 4u);
  EXPECT_EQ(all.first_inverted, 5);
  const TetForceStatus tail = kernel()(m.args(), 7, 11);
  EXPECT_EQ(tail.inverted, 2u);
  EXPECT_EQ(tail.first_inverted, 8);
  for (int t : {5, 6, 8, 9, 10}) {
    for (int n = 0; n < 12; ++n) EXPECT_EQ(m.force[12 * t + n], 0.0);
    for (int n = 0; n < 6; ++n) EXPECT_EQ(m.stress[6 * t + n], 0.0);
    EXPECT_EQ(m.energy[t], 0.0);
  }
  for (double f : m.force) EXPECT_TRUE(std::isfinite(f));
  EXPECT_EQ(m.force[12 * 4], 0.0);  // tet 4 is undeformed: zero force, but computed
}

// 4. The vector path against the scalar reference on 10^4 random tets: 4 materials (with viscosity), node
// ids shuffled (general gathers), strains up to ~15 % (both log branches), a few inverted tets, and ranges
// split into pieces of 1..9 tets so every tail length occurs. Both paths evaluate the same expressions and
// differ only by the compiler's choice of fused multiply-adds, i.e. a few ulps per operation on ~400
// operations: 1e-12 of each tet's largest entry is a fair bound. Splitting must not change any bit.
TEST(TetForces, VectorMatchesScalarReference) {
  constexpr size_t kTets = 10000;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mesh m;
  std::vector<int32_t> perm(4 * kTets);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  m.x0.resize(12 * kTets);
  m.x.resize(12 * kTets);
  m.v.resize(12 * kTets);
  for (size_t t = 0; t < kTets; ++t) {
    const double strain = t % 3 == 0 ? 0.15 : 1e-3;
    Mat3 A;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) A[i][k] = (i == k) + strain * u(rng);
    const double corner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int a = 0; a < 4; ++a) {
      const size_t n = static_cast<size_t>(perm[4 * t + a]);
      m.tets.push_back(static_cast<int32_t>(n));
      for (int i = 0; i < 3; ++i) m.x0[3 * n + i] = 0.01 * (corner[a][i] + 0.2 * u(rng)) + 0.1 * t;
      for (int i = 0; i < 3; ++i) m.v[3 * n + i] = 0.1 * u(rng);
    }
    for (int a = 0; a < 4; ++a) {
      const size_t n = static_cast<size_t>(perm[4 * t + a]);
      for (int i = 0; i < 3; ++i)
        m.x[3 * n + i] =
            A[i][0] * m.x0[3 * n] + A[i][1] * m.x0[3 * n + 1] + A[i][2] * m.x0[3 * n + 2] + 0.01 * u(rng);
    }
    if (t % 997 == 500) {  // push corner 3 through the opposite face
      const size_t n0 = static_cast<size_t>(perm[4 * t]), n3 = static_cast<size_t>(perm[4 * t + 3]);
      for (int i = 0; i < 3; ++i) m.x[3 * n3 + i] = 2 * m.x[3 * n0 + i] - m.x[3 * n3 + i];
    }
  }
  ASSERT_EQ(m.prepare(), 0u);
  m.materials = {{16e9, 16e9, 1e5}, {8e9, 12e9, 0.0}, {30e9, 5e9, 3e4}, {1e9, 2e9, 1e3}};
  for (size_t t = 0; t < kTets; ++t) m.material[t] = static_cast<int32_t>((t * 7) % 4);

  const TetForceStatus ref_status = m.run(&tet_forces_scalar);
  const std::vector<double> ref_force = m.force, ref_stress = m.stress, ref_energy = m.energy;
  EXPECT_GE(ref_status.inverted, 10u);
  const TetForceStatus vec_status = m.run(&tet_forces);
  EXPECT_EQ(vec_status.inverted, ref_status.inverted);
  EXPECT_EQ(vec_status.first_inverted, ref_status.first_inverted);
  double worst = 0.0;
  for (size_t t = 0; t < kTets; ++t) {
    const double* fr = &ref_force[12 * t];
    const double* sr = &ref_stress[6 * t];
    double fscale = 0.0, sscale = 0.0;
    for (int n = 0; n < 12; ++n) fscale = std::max(fscale, std::fabs(fr[n]));
    for (int n = 0; n < 6; ++n) sscale = std::max(sscale, std::fabs(sr[n]));
    for (int n = 0; n < 12; ++n) worst = std::max(worst, std::fabs(m.force[12 * t + n] - fr[n]) / fscale);
    for (int n = 0; n < 6; ++n) worst = std::max(worst, std::fabs(m.stress[6 * t + n] - sr[n]) / sscale);
    if (ref_energy[t] != 0.0)
      worst = std::max(worst, std::fabs(m.energy[t] / ref_energy[t] - 1.0));
    else
      EXPECT_EQ(m.energy[t], 0.0);
  }
  EXPECT_LT(worst, 1e-12);
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", worst);
  RecordProperty("worst_relative_difference", text);

  // The same vector computation split into ranges of 1..9 tets: every bit identical.
  const std::vector<double> vec_force = m.force, vec_stress = m.stress, vec_energy = m.energy;
  std::fill(m.force.begin(), m.force.end(), -1.0);
  size_t inverted = 0;
  for (size_t begin = 0, len = 1; begin < kTets; begin += len, len = len % 9 + 1)
    inverted += tet_forces(m.args(), begin, std::min(kTets, begin + len)).inverted;
  EXPECT_EQ(inverted, ref_status.inverted);
  EXPECT_TRUE(m.force == vec_force);
  EXPECT_TRUE(m.stress == vec_stress);
  EXPECT_TRUE(m.energy == vec_energy);
}

// Skipping stress and energy (empty spans) leaves the forces unchanged.
TEST_P(BothPaths, OptionalOutputsMaySkip) {
  Mesh m = cube_patch();
  ASSERT_EQ(m.prepare(), 0u);
  m.map({{{1.01, 0.02, 0.0}, {0.0, 0.99, 0.03}, {0.01, 0.0, 1.02}}}, {0, 0, 0});
  m.run(kernel());
  const std::vector<double> full = m.force;
  TetForceArgs a = m.args();
  a.stress = {};
  a.strain_energy = {};
  kernel()(a, 0, m.num_tets());
  EXPECT_TRUE(m.force == full);
}

// 6. Regular tet of edge a: every altitude is sqrt(2/3) a, so dt = sqrt(2/3) a / c_p. A handful of roundings
// separate the two sides: 1e-14 relative.
TEST(StableStep, RegularTetAltitudeOverWaveSpeed) {
  const double s = 0.0125;  // edge a = 2 sqrt(2) s
  const double a = 2.0 * std::sqrt(2.0) * s;
  std::vector<double> x = {s, s, s, s, -s, -s, -s, s, -s, -s, -s, s};
  std::vector<int32_t> tets = {0, 1, 2, 3};
  std::vector<double> dm(9), vol(1);
  if (tet_prepare(x, tets, dm, vol, 0, 1) != 0) std::swap(tets[2], tets[3]);
  ASSERT_EQ(tet_prepare(x, tets, dm, vol, 0, 1), 0u);
  const std::vector<int32_t> material = {0};
  const std::vector<TetMaterial> materials = {kRock};
  const std::vector<double> density = {2650.0};
  const double c_p = std::sqrt((kRock.lambda + 2 * kRock.mu) / density[0]);
  const double dt = tet_stable_step(x, tets, material, materials, density, 0, 1);
  EXPECT_NEAR(dt, std::sqrt(2.0 / 3.0) * a / c_p, 1e-14 * dt);
  EXPECT_TRUE(std::isinf(tet_stable_step(x, tets, material, materials, density, 0, 0)));

  // Viscous reduction: xi = eta / (M dt_e) = 3/4 gives sqrt(1 + 9/16) - 3/4 = 1/2 exactly.
  const double M = kRock.lambda + 2 * kRock.mu;
  EXPECT_NEAR(viscous_stable_step(dt, 0.75 * M * dt, M), 0.5 * dt, 1e-15 * dt);
  EXPECT_NEAR(viscous_stable_step(dt, 0.0, M), dt, 4e-16 * dt);
  const std::vector<TetMaterial> damped = {{kRock.lambda, kRock.mu, 0.75 * M * dt}};
  EXPECT_NEAR(tet_damped_stable_step(x, tets, material, damped, density, 0, 1), 0.5 * dt, 1e-15 * dt);
}

// Two tets, the smaller one soft: the minimum is taken over tets with their own material.
TEST(StableStep, MinimumOverTetsAndMaterials) {
  std::vector<double> x = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 5, 5, 5.5, 5, 5, 5, 5.5, 5, 5, 5, 5.5};
  std::vector<int32_t> tets = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<TetMaterial> materials = {kRock, {1e9, 1e9, 0.0}};
  const std::vector<double> density = {2650.0, 2000.0};
  // Corner tet of legs L: largest face is the slanted one, area sqrt(3)/2 L^2, V = L^3/6 -> h = L / sqrt(3).
  const double h_big = 1.0 / std::sqrt(3.0), h_small = 0.5 / std::sqrt(3.0);
  const double c0 = std::sqrt(48e9 / 2650.0), c1 = std::sqrt(3e9 / 2000.0);
  for (int32_t soft : {0, 1}) {
    const std::vector<int32_t> material = {1 - soft, soft};
    const double expected = std::min(h_big / (soft ? c0 : c1), h_small / (soft ? c1 : c0));
    EXPECT_NEAR(tet_stable_step(x, tets, material, materials, density, 0, 2), expected, 1e-14 * expected);
  }
}

// tet_prepare on the unit corner tet: Dm^-1 = I and V0 = 1/6 exactly.
TEST(TetPrepare, UnitCornerTet) {
  Mesh m;
  m.x0 = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  m.tets = {0, 1, 2, 3};
  ASSERT_EQ(m.prepare(), 0u);
  EXPECT_EQ(m.volume0[0], 1.0 / 6.0);
  for (int n = 0; n < 9; ++n) EXPECT_EQ(m.dm_inv[n], n % 4 == 0 ? 1.0 : 0.0);
  m.tets = {0, 2, 1, 3};  // reversed orientation
  EXPECT_EQ(m.prepare(), 1u);
  EXPECT_EQ(m.volume0[0], 0.0);
}

}  // namespace
}  // namespace rift::kernels
