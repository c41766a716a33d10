// Tet kernels with an initial (in-situ) stress sigma0: the corner forces of a prestressed tet, equilibrium
// of a prestressed patch loaded by sigma0 n on its boundary, and the prestress energy V0 S0 : E (S0 = sigma0
// a constant second Piola-Kirchhoff stress, E the Green-Lagrange strain), the exact potential of its forces.
// Every check runs on both tet_forces_scalar and tet_forces (their bitwise agreement with a prestress is in
// test_tet_kernels.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "kernels/tet_forces.hpp"
#include "tests/unit/test_tet_support.hpp"

namespace rift::kernels {
namespace {

using namespace tet_test;

INSTANTIATE_TEST_SUITE_P(TetForces, BothPaths, both_paths, path_name);

// A general in-situ stress: compressive, anisotropic, with shear [Pa].
constexpr double kSigma0[6] = {-20e6, -12e6, -30e6, 4e6, -3e6, 5e6};

std::array<double, 3> node_position(const Mesh& m, int32_t n) {
  return {m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]};
}
std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
std::array<double, 3> minus(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
std::array<double, 3> times(const double* s, const std::array<double, 3>& a) {  // s a, s in Voigt order
  return {s[0] * a[0] + s[3] * a[1] + s[5] * a[2], s[3] * a[0] + s[1] * a[1] + s[4] * a[2],
          s[5] * a[0] + s[4] * a[1] + s[2] * a[2]};
}
std::array<double, 3> times_sigma0(const std::array<double, 3>& a) {
  return times(kSigma0, a);
}

// R s R^T in Voigt order.
std::array<double, 6> turned(const Mat3& R, const double* s) {
  const double S[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  static constexpr int row[6] = {0, 1, 2, 0, 1, 2}, col[6] = {0, 1, 2, 1, 2, 0};
  std::array<double, 6> out{};
  for (int n = 0; n < 6; ++n)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) out[n] += R[row[n]][i] * S[i][k] * R[col[n]][k];
  return out;
}

// Rotation by angle about the unit axis u (Rodrigues).
Mat3 rotation(std::array<double, 3> u, double angle) {
  const double norm = std::sqrt(dot(u, u));
  for (double& c : u) c /= norm;
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 R;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) R[i][k] = (i == k ? c : 0.0) + (1 - c) * u[i] * u[k];
  R[0][1] -= s * u[2], R[0][2] += s * u[1], R[1][0] += s * u[2];
  R[1][2] -= s * u[0], R[2][0] -= s * u[1], R[2][1] += s * u[0];
  return R;
}

// A material without stiffness or viscosity isolates the prestress: the stress is then sigma0 exactly.
Mesh prestressed(Mesh m, TetMaterial material) {
  m.materials = {material};
  m.initial_stress.assign(kSigma0, kSigma0 + 6);
  EXPECT_EQ(m.prepare(), 0u);
  return m;
}

// 1. An unstrained tet, as built and turned rigidly (90 degrees about z, and 0.7 rad about a general axis):
// the prestress turns with the material, so the stress is R sigma0 R^T and corner a carries
// -V (R sigma0 R^T) grad_x N_a. grad N_a, independently of the kernel: normal to the opposite face (b, c, d),
// c_a = (x_c - x_b) x (x_d - x_b), scaled so that (x_a - x_b).grad N_a = 1, and V = |c_a.(x_a - x_b)| / 6.
// F = R only to the rounding of the edges and Dm^-1 (~1e-16), so a few roundings on both sides: 1e-14 of
// the largest force and of |sigma0| (also unturned: F - I is ~1e-16, not 0). The four forces sum to
// zero (f_0 is formed as minus the others), to the round-off of the largest one.
TEST_P(BothPaths, PrestressedTetCornerForces) {
  const Mat3 turns[3] = {{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                         {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}},
                         rotation({1.0, -2.0, 3.0}, 0.7)};
  double scale = 0.0;
  for (double s : kSigma0) scale = std::max(scale, std::fabs(s));
  for (int turn = 0; turn < 3; ++turn) {
    const Mat3& R = turns[turn];
    Mesh m = prestressed(general_tet(), {0.0, 0.0, 0.0});
    m.map(R, {0.5, -1.0, 2.0});
    EXPECT_EQ(m.run(kernel()).inverted, 0u);
    const std::array<double, 6> sigma = turned(R, kSigma0);
    for (int n = 0; n < 6; ++n) {
      EXPECT_NEAR(m.stress[n], sigma[n], 1e-14 * scale) << "turn " << turn << " component " << n;
    }
    double largest = 0.0;
    for (double f : m.force) largest = std::max(largest, std::fabs(f));
    for (int a = 0; a < 4; ++a) {
      const int b = (a + 1) % 4, c = (a + 2) % 4, d = (a + 3) % 4;
      const auto xb = node_position(m, b);
      const auto normal = cross(minus(node_position(m, c), xb), minus(node_position(m, d), xb));
      const double height = dot(normal, minus(node_position(m, a), xb));
      const double volume = std::fabs(height) / 6.0;
      const auto s_grad = times(sigma.data(), normal);
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(m.force[3 * a + i], -volume * s_grad[i] / height, 1e-14 * largest)
            << "turn " << turn << " corner " << a;
    }
    for (int i = 0; i < 3; ++i)
      EXPECT_LE(std::fabs(m.force[i] + m.force[3 + i] + m.force[6 + i] + m.force[9 + i]), 1e-15 * largest);
  }
}

// 2. Equilibrium at t = 0: the jittered 48-tet patch of rock, undeformed, with uniform sigma0 and the
// boundary traction sigma0 n lumped a third per corner of each boundary face. Every node's total force
// vanishes: the internal forces around a node are sigma0 times the area vectors of the faces opposite it,
// which close up (interior node) or are closed by the boundary faces. Round-off: x = X exactly, but F - I
// from the edges and Dm^-1 carries ~1e-15, i.e. an elastic stress of ~1e-15 E, 2e-12 of |sigma0| here, on
// each of up to 24 tets at a node; 1e-10 of the largest corner force covers that.
TEST_P(BothPaths, PrestressedPatchWithBoundaryTractionIsInEquilibrium) {
  Mesh m = prestressed(cube_patch(), kRock);
  EXPECT_EQ(m.run(kernel()).inverted, 0u);
  std::vector<double> total(m.x.size(), 0.0);
  double largest = 0.0;
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        total[3 * m.tets[4 * t + a] + i] += m.force[12 * t + 3 * a + i];
        largest = std::max(largest, std::fabs(m.force[12 * t + 3 * a + i]));
      }
  // Boundary faces: those of exactly one tet; outward = away from that tet's fourth corner.
  std::map<std::array<int32_t, 3>, std::pair<int, std::array<int32_t, 4>>> faces;
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int32_t, 4> face_and_opposite;
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != skip) face_and_opposite[k++] = m.tets[4 * t + a];
      face_and_opposite[3] = m.tets[4 * t + skip];
      std::array<int32_t, 3> key = {face_and_opposite[0], face_and_opposite[1], face_and_opposite[2]};
      std::sort(key.begin(), key.end());
      auto& entry = faces[key];
      ++entry.first;
      entry.second = face_and_opposite;
    }
  int boundary = 0;
  for (const auto& [key, entry] : faces) {
    if (entry.first != 1) continue;
    ++boundary;
    const auto& f = entry.second;
    const auto x0 = node_position(m, f[0]);
    auto area = cross(minus(node_position(m, f[1]), x0), minus(node_position(m, f[2]), x0));  // 2 A n
    if (dot(area, minus(node_position(m, f[3]), x0)) > 0)
      for (double& c : area) c = -c;
    const auto load = times_sigma0(area);  // 2 A sigma0 n
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) total[3 * f[k] + i] += load[i] / 6.0;
  }
  EXPECT_EQ(boundary, 48);  // 2 x 2 squares per side, 2 triangles each, 6 sides
  for (size_t n = 0; n < total.size(); ++n) EXPECT_LT(std::fabs(total[n]), 1e-10 * largest) << "dof " << n;
}

// 3. The energy output adds V0 S0 : E. Undeformed, the prestress forces are exactly minus its gradient:
// central differences with step 1e-6 of the tet size, as in test_tet_kernels.cpp (the elastic part has zero
// gradient at F = I and is even to second order), bound 1e-6 of the largest force.
TEST_P(BothPaths, PrestressEnergyGradientIsTheForceWhenUndeformed) {
  Mesh m = prestressed(general_tet(), kRock);
  expect_force_is_minus_energy_gradient(m, kernel(), 1e-6, 1e-6, "");
}

// 4. Deformed and turned far from the reference (5 % and 20 % strain, then 0.7 and 2.5 rad about a general
// axis), the forces stay minus the gradient of the booked energy: the prestress has an exact potential. With
// a material of no stiffness the energy is the prestress energy alone, so the check sees nothing else; with
// rock, the sum. Central differences with step 1e-6 of the tet size: truncation ~1e-12 and roundoff
// ~1e-16 / 1e-6 relative, so 1e-6 of the largest force is fair. A Cauchy prestress held fixed in space
// fails this check in every one of these states.
TEST_P(BothPaths, PrestressForcesAreMinusEnergyGradientAtLargeTurns) {
  const Mat3 g = {{{0.9, 0.4, -0.3}, {-0.2, 0.5, 0.7}, {0.35, -0.6, 1.0}}};
  for (TetMaterial material : {TetMaterial{0.0, 0.0, 0.0}, kRock})
    for (double strain : {5e-2, 2e-1})
      for (double angle : {0.7, 2.5}) {
        Mesh m = prestressed(general_tet(), material);
        const Mat3 R = rotation({1.0, -2.0, 3.0}, angle);
        Mat3 A{};
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) A[i][k] += R[i][l] * ((l == k) + strain * g[l][k]);
        m.map(A, {0.1, 0.2, 0.3});
        char context[96];
        std::snprintf(context, sizeof context, ", mu %.0e, strain %.2f, angle %.1f", material.mu, strain,
                      angle);
        expect_force_is_minus_energy_gradient(m, kernel(), 1e-6, 1e-6, context);
      }
}

// 5. The booked prestress energy (energy with sigma0 minus energy without) is V0 S0 : E with the
// Green-Lagrange strain E = (F^T F - I) / 2, formed here from F directly. At 1 % strain the energies are ~4e6
// V0 (elastic) and ~3e5 V0 (prestress): their difference leaves rounding ~1e-9 V0, so 1e-10 of the booked
// value.
TEST_P(BothPaths, PrestressEnergyIsGreenLagrangeWork) {
  const Mat3 H = {{{0.010, 0.004, -0.003}, {-0.002, -0.006, 0.005}, {0.007, 0.001, 0.008}}};
  auto energy = [&](bool with_prestress) {
    Mesh m = general_tet();
    EXPECT_EQ(m.prepare(), 0u);
    if (with_prestress) m.initial_stress.assign(kSigma0, kSigma0 + 6);
    m.map(identity_plus(H), {0.0, 0.0, 0.0});
    m.run(kernel());
    return std::pair{m.energy[0], m.volume0[0]};
  };
  const auto [with, volume0] = energy(true);
  const double booked = with - energy(false).first;
  const Mat3 F = identity_plus(H);
  static constexpr int row[6] = {0, 1, 2, 0, 1, 2}, col[6] = {0, 1, 2, 1, 2, 0};
  double expected = 0.0;
  for (int n = 0; n < 6; ++n) {
    double c = 0.0;  // (F^T F)_ab
    for (int k = 0; k < 3; ++k) c += F[k][row[n]] * F[k][col[n]];
    const double green = 0.5 * (c - (row[n] == col[n]));
    expected += (row[n] == col[n] ? 1.0 : 2.0) * kSigma0[n] * green;
  }
  expected *= volume0;
  EXPECT_NEAR(booked, expected, 1e-10 * std::fabs(expected));
}

}  // namespace
}  // namespace rift::kernels
