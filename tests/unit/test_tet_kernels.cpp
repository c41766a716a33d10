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
#include "tests/unit/test_tet_support.hpp"

namespace rift::kernels {
namespace {

using namespace tet_test;

INSTANTIATE_TEST_SUITE_P(TetForces, BothPaths, both_paths, path_name);

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

// A general tet strained by A (5 %, so J != 1 matters) with the velocities of a homogeneous spatial velocity
// gradient, v = L x + c, and a viscous material. Returns sym L.
Mat3 strained_tet_with_velocity_gradient(Mesh& m, const Mat3& L) {
  m = general_tet();
  m.materials = {{kRock.lambda, kRock.mu, 2e5}};
  EXPECT_EQ(m.prepare(), 0u);
  m.map(identity_plus({{{0.05, 0.01, -0.02}, {0.03, -0.04, 0.02}, {0.0, 0.01, 0.03}}}), {0.1, 0.2, -0.3});
  for (int n = 0; n < 4; ++n)
    for (int i = 0; i < 3; ++i)
      m.v[3 * n + i] = L[i][0] * m.x[3 * n] + L[i][1] * m.x[3 * n + 1] + L[i][2] * m.x[3 * n + 2] + 0.7;
  Mat3 D;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) D[i][k] = 0.5 * (L[i][k] + L[k][i]);
  return D;
}

double current_volume(const Mesh& m) {  // triple product of the current edges / 6
  double e[3][3];
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) e[c][i] = m.x[3 * (c + 1) + i] - m.x[i];
  return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
          e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
          e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}

// 7. Viscous power P = eta (D:D) V for a homogeneous velocity gradient (D = sym L exactly). The kernel
// recovers L from velocity differences through F^-1 (cof / J): a few tens of roundings on a well-shaped tet,
// so 1e-13 relative is fair. The viscous stress (stress minus that of the same tet at rest) is eta D: there
// the elastic stress, ~1e3 times larger here, is cancelled, so its rounding (1e-16 of it) sets 1e-12 of
// |eta D| as the bound.
TEST_P(BothPaths, ViscousPowerOfHomogeneousVelocityGradient) {
  Mesh m;
  const Mat3 L = {{{3.0, -1.5, 0.5}, {2.0, -1.0, 4.0}, {-0.5, 1.0, 2.5}}};
  const Mat3 D = strained_tet_with_velocity_gradient(m, L);
  const double eta = m.materials[0].eta;
  EXPECT_EQ(m.run(kernel()).inverted, 0u);
  double dd = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) dd += D[i][k] * D[i][k];
  const double expected = eta * dd * current_volume(m);
  EXPECT_NEAR(m.power[0], expected, 1e-13 * expected);
  const std::vector<double> moving = m.stress;
  std::fill(m.v.begin(), m.v.end(), 0.0);
  m.run(kernel());
  EXPECT_EQ(m.power[0], 0.0);
  const double eta_d[6] = {eta * D[0][0], eta * D[1][1], eta * D[2][2],
                           eta * D[0][1], eta * D[1][2], eta * D[2][0]};
  double diff[6];
  for (int n = 0; n < 6; ++n) diff[n] = moving[n] - m.stress[n] - eta_d[n];
  EXPECT_LT(norm6(diff), 1e-12 * norm6(eta_d));
}

// A rigid spin (L antisymmetric) of the strained tet dissipates nothing: D vanishes up to the rounding of the
// velocities, ~1e-16 |L| relative, so P is ~1e-32 of eta |L|^2 V; 1e-24 leaves room for conditioning and is
// still 24 orders below the power of a comparable stretching rate.
TEST_P(BothPaths, ViscousPowerVanishesForRigidSpin) {
  Mesh m;
  const Mat3 W = {{{0.0, -3.0, 1.5}, {3.0, 0.0, -2.0}, {-1.5, 2.0, 0.0}}};
  strained_tet_with_velocity_gradient(m, W);
  m.run(kernel());
  double ww = 0.0;
  for (const auto& row : W)
    for (double w : row) ww += w * w;
  const double scale = m.materials[0].eta * ww * current_volume(m);
  EXPECT_GE(m.power[0], 0.0);
  EXPECT_LT(m.power[0], 1e-24 * scale);
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
    // h = 1e-6 of the tet size (~1); bound 1e-6 of the largest force.
    expect_force_is_minus_energy_gradient(m, kernel(), 1e-6, 1e-6, ", strain scale " + std::to_string(scale));
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

// 10^4 random tets of size 0.01: 4 materials (three viscous), node ids shuffled (general gathers), strains
// up to ~15 % (both log branches) plus a 1 % random perturbation of each corner, random velocities, and every
// 997th tet inverted.
Mesh random_tets(size_t count) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mesh m;
  std::vector<int32_t> perm(4 * count);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  m.x0.resize(12 * count);
  m.x.resize(12 * count);
  m.v.resize(12 * count);
  for (size_t t = 0; t < count; ++t) {
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
            A[i][0] * m.x0[3 * n] + A[i][1] * m.x0[3 * n + 1] + A[i][2] * m.x0[3 * n + 2] + 1e-4 * u(rng);
    }
    if (t % 997 == 500) {  // push corner 3 through the opposite face
      const size_t n0 = static_cast<size_t>(perm[4 * t]), n3 = static_cast<size_t>(perm[4 * t + 3]);
      for (int i = 0; i < 3; ++i) m.x[3 * n3 + i] = 2 * m.x[3 * n0 + i] - m.x[3 * n3 + i];
    }
  }
  EXPECT_EQ(m.prepare(), 0u);
  m.materials = {{16e9, 16e9, 1e5}, {8e9, 12e9, 0.0}, {30e9, 5e9, 3e4}, {1e9, 2e9, 1e3}};
  for (size_t t = 0; t < count; ++t) m.material[t] = static_cast<int32_t>((t * 7) % 4);
  return m;
}

// Worst difference of the vector outputs from the reference, relative to each tet's largest force and
// stress entry, its power and energy_scale[t] for the energy.
double worst_difference(const Mesh& vec, const Mesh& ref, const std::vector<double>& energy_scale) {
  double worst = 0.0;
  auto close = [&](double a, double b, double scale) {
    if (a != b) worst = std::max(worst, std::fabs(a - b) / scale);
  };
  for (size_t t = 0; t < ref.num_tets(); ++t) {
    double fscale = 1e-300, sscale = 1e-300;
    for (int n = 0; n < 12; ++n) fscale = std::max(fscale, std::fabs(ref.force[12 * t + n]));
    for (int n = 0; n < 6; ++n) sscale = std::max(sscale, std::fabs(ref.stress[6 * t + n]));
    for (int n = 0; n < 12; ++n) close(vec.force[12 * t + n], ref.force[12 * t + n], fscale);
    for (int n = 0; n < 6; ++n) close(vec.stress[6 * t + n], ref.stress[6 * t + n], sscale);
    close(vec.energy[t], ref.energy[t], energy_scale[t] + 1e-300);
    close(vec.power[t], ref.power[t], ref.power[t] + 1e-300);
  }
  return worst;
}

// 4. The vector path against the scalar reference on random_tets, first with the base outputs, then with
// viscous power and an initial stress per material (tens of MPa, of the order of the elastic stresses).
// Both paths evaluate the same expressions in the same order and differ only where gcc fuses a multiply
// and an add in one and not in the other (it contracts by default in C++). The largest effect: the diagonal
// of H = F - I comes from rounding F ~ I, so the two H differ by an ulp of 1 (2e-16 absolute), which at the
// ~1e-2 strains here and lambda / mu up to 6 is ~1e-13 of the stress; 1e-12 of each tet's largest entry is a
// fair bound (measured: 2e-13). The energy with a prestress is a sum of the elastic and prestress energies,
// which can cancel: it is compared relative to the sum of their magnitudes. Ranges split into pieces of 1..9
// tets (every tail length) must not change any bit.
TEST(TetForces, VectorMatchesScalarReference) {
  constexpr size_t kTets = 10000;
  Mesh ref = random_tets(kTets);
  std::vector<double> elastic_energy(kTets), energy_scale(kTets);
  for (bool extras : {false, true}) {
    if (extras) {
      std::mt19937_64 rng(77);
      std::uniform_real_distribution<double> u(-30e6, 30e6);
      ref.initial_stress.resize(6 * ref.materials.size());
      for (double& s : ref.initial_stress) s = u(rng);
    }
    auto run = [&](Mesh& m, ForceFn fn, size_t begin, size_t end) {
      TetForceArgs a = m.args();
      if (!extras) a.viscous_power = {};
      return fn(a, begin, end);
    };
    Mesh vec = ref;
    const TetForceStatus ref_status = run(ref, &tet_forces_scalar, 0, kTets);
    EXPECT_GE(ref_status.inverted, 10u);
    const TetForceStatus vec_status = run(vec, &tet_forces, 0, kTets);
    EXPECT_EQ(vec_status.inverted, ref_status.inverted);
    EXPECT_EQ(vec_status.first_inverted, ref_status.first_inverted);
    for (size_t t = 0; t < kTets; ++t) {
      if (!extras) elastic_energy[t] = ref.energy[t];
      energy_scale[t] = std::fabs(elastic_energy[t]) + std::fabs(ref.energy[t] - elastic_energy[t]);
    }
    const double worst = worst_difference(vec, ref, energy_scale);
    EXPECT_LT(worst, 1e-12) << "extras " << extras;
    char text[32];
    std::snprintf(text, sizeof text, "%.3e", worst);
    RecordProperty(extras ? "worst_relative_difference_extras" : "worst_relative_difference", text);
    if (extras)
      for (size_t t = 0; t < kTets; ++t) {
        const bool live = ref.materials[static_cast<size_t>(ref.material[t])].eta > 0 && ref.energy[t] != 0.0;
        EXPECT_EQ(ref.power[t] > 0.0, live) << "tet " << t;
        EXPECT_GE(ref.power[t], 0.0);
      }

    Mesh split = ref;
    for (auto* out : {&split.force, &split.stress, &split.energy, &split.power})
      std::fill(out->begin(), out->end(), -1.0);
    size_t inverted = 0;
    for (size_t begin = 0, len = 1; begin < kTets; begin += len, len = len % 9 + 1)
      inverted += run(split, &tet_forces, begin, std::min(kTets, begin + len)).inverted;
    EXPECT_EQ(inverted, ref_status.inverted);
    EXPECT_TRUE(split.force == vec.force);
    EXPECT_TRUE(split.stress == vec.stress);
    EXPECT_TRUE(split.energy == vec.energy);
    EXPECT_TRUE(split.power == vec.power);
  }
}

// Skipping stress, energy and power (empty spans) leaves the forces unchanged to the last bit, with and
// without an initial stress: the outputs are formed after the forces by the same compiled law.
TEST_P(BothPaths, OptionalOutputsMaySkip) {
  for (bool prestress : {false, true}) {
    Mesh m = cube_patch();
    m.materials = {{kRock.lambda, kRock.mu, 1e5}};
    if (prestress) m.initial_stress = {-20e6, -12e6, -30e6, 4e6, -3e6, 5e6};
    ASSERT_EQ(m.prepare(), 0u);
    m.map({{{1.01, 0.02, 0.0}, {0.0, 0.99, 0.03}, {0.01, 0.0, 1.02}}}, {0, 0, 0});
    for (size_t n = 0; n < m.v.size(); ++n) m.v[n] = 0.1 * std::sin(1.0 + n);
    m.run(kernel());
    const std::vector<double> full = m.force;
    TetForceArgs a = m.args();
    a.stress = {};
    a.strain_energy = {};
    a.viscous_power = {};
    kernel()(a, 0, m.num_tets());
    EXPECT_TRUE(m.force == full) << "prestress " << prestress;
  }
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
