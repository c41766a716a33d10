// Selective mass scaling (solid.mass_scaling_step) and the per-node stable step it rests on
// (kernels/stable_step.hpp): each node's bound K_n / m_n from its tet and its joints, checked against the
// global estimates it refines and against the highest frequency of a tet found independently (power
// iteration on its stiffness by finite differences), then the scaling itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/stable_step.hpp"
#include "kernels/tet_forces.hpp"
#include "tests/unit/test_tet_support.hpp"

namespace rift::kernels {
namespace {

using namespace tet_test;

constexpr double kDensity = 2650.0;

std::vector<double> tet_corner_masses(Mesh& m) {
  m.prepare();
  return std::vector<double>(4, kDensity * m.volume0[0] / 4.0);
}

// The tet as a fracture zone's: its exact step, its mass rho V.
std::vector<double> tet_node_stiffness(const Mesh& m) {
  std::vector<double> k(4, 0.0);
  const std::vector<double> density{kDensity};
  const std::vector<double> step{tet_exact_stable_step(m.x0, m.tets, m.material, m.materials, density, 0, 1)};
  const std::vector<double> mass{kDensity * m.volume0[0]};
  add_tet_node_stiffness(m.tets, step, mass, k);
  return k;
}

// Largest eigenvalue of M^-1/2 K M^-1/2 for the tet's 12 x 12 stiffness, K by central differences of the
// scalar kernel's forces about the reference state (linear there: Hooke at small strain).
double highest_omega2(Mesh& m, const std::vector<double>& mass) {
  double K[12][12];
  const double eps = 1e-9;
  for (int c = 0; c < 12; ++c) {
    const double keep = m.x[c];
    m.x[c] = keep + eps;
    m.run(tet_forces_scalar);
    const std::vector<double> plus = m.force;
    m.x[c] = keep - eps;
    m.run(tet_forces_scalar);
    m.x[c] = keep;
    for (int r = 0; r < 12; ++r) K[r][c] = -(plus[r] - m.force[r]) / (2 * eps);
  }
  std::vector<double> v(12), w(12);
  for (int r = 0; r < 12; ++r) v[r] = 1.0 + 0.1 * r * (r % 2 ? -1 : 1);
  double lambda = 0.0;
  for (int it = 0; it < 2000; ++it) {
    double norm = 0.0, vw = 0.0, vv = 0.0;
    for (int r = 0; r < 12; ++r) {
      w[r] = 0.0;
      for (int c = 0; c < 12; ++c) w[r] += K[r][c] / std::sqrt(mass[r / 3] * mass[c / 3]) * v[c];
      norm += w[r] * w[r];
      vw += v[r] * w[r];
      vv += v[r] * v[r];
    }
    lambda = vw / vv;
    norm = std::sqrt(norm);
    for (int r = 0; r < 12; ++r) v[r] = w[r] / norm;
  }
  return lambda;
}

// With the tet's own corner masses each node's step is the tet's exact one, 2 / omega_max with omega_max
// from the power iteration above: they agree to the finite differences' error (~1e-6; 1e-5 allowed). The
// h / c_p estimate (tet_stable_step) is above it on this tet: printed, and docs/stability.md keeps it.
// With damping, the viscous reduction applies to the exact step as it does to the estimate.
TEST(NodeStableStep, ALoneTetsCornersHaveItsExactStep) {
  Mesh m = general_tet();
  const std::vector<double> mass = tet_corner_masses(m);
  m.x = m.x0;
  const double exact = 2.0 / std::sqrt(highest_omega2(m, mass));
  EXPECT_NEAR(node_stable_step(tet_node_stiffness(m), mass), exact, 1e-5 * exact);
  const std::vector<double> density{kDensity};
  const double estimate = tet_stable_step(m.x0, m.tets, m.material, m.materials, density, 0, 1);
  std::printf("general tet: h / c_p = %.4g s, exact step %.4g s (estimate / exact = %.3f)\n", estimate, exact,
              estimate / exact);
  const double M = kRock.lambda + 2 * kRock.mu;
  m.materials[0].eta = 0.75 * M * exact;  // xi = 3/4 at the exact step: the reduction is exactly 1/2
  EXPECT_NEAR(node_stable_step(tet_node_stiffness(m), mass), 0.5 * exact, 1e-5 * exact);
}

// The bound against the tet's highest frequency with unequal masses, as mass scaling makes them: a heavier
// node lowers every Rayleigh quotient, so omega_max^2 <= the equal-mass value / (smallest mass factor) =
// max_n K_n / m_n. Checked on factors up to 16 (the finite differences' 1e-5 allowed).
TEST(NodeStableStep, BoundsTheTetsHighestFrequencyWithScaledMasses) {
  Mesh m = general_tet();
  const std::vector<double> base = tet_corner_masses(m);
  m.x = m.x0;
  const std::vector<double> k = tet_node_stiffness(m);
  const std::vector<std::vector<double>> factors = {
      {1, 1, 1, 1}, {4, 1, 1, 1}, {16, 2, 1, 8}, {3, 3, 3, 3}, {2, 5, 9, 16}};
  for (const auto& f : factors) {
    std::vector<double> mass(4);
    double bound = 0.0;
    for (int n = 0; n < 4; ++n) {
      mass[n] = base[n] * f[n];
      bound = std::max(bound, k[n] / mass[n]);
    }
    const double omega2 = highest_omega2(m, mass);
    EXPECT_LE(omega2, bound * (1 + 1e-5)) << "factors " << f[0] << " " << f[1] << " " << f[2] << " " << f[3];
    std::printf("mass factors %g %g %g %g: omega_max^2 / bound = %.3f\n", f[0], f[1], f[2], f[3],
                omega2 / bound);
  }
}

// The scaling: nodes whose step 2 sqrt(m / K) is below the target get m = K step^2 / 4 (their step is then
// the target to round-off), the others and massless nodes keep theirs, and the totals add up.
TEST(MassScaling, LiftsOnlyTheNodesBelowTheStep) {
  const double step = 1e-8;
  // K chosen so the steps are 0.5, 1, 2 and 0.25 x the target; node 4 massless (follows its BCs).
  std::vector<double> mass = {1e-3, 1e-3, 1e-3, 2e-3, 0.0};
  std::vector<double> stiffness(5);
  const double ratio[5] = {0.5, 1.0, 2.0, 0.25, 0.5};
  for (int n = 0; n < 5; ++n) stiffness[n] = 4.0 * (n == 4 ? 1e-3 : mass[n]) / std::pow(ratio[n] * step, 2);
  std::vector<double> inv_mass(5);
  for (int n = 0; n < 5; ++n) inv_mass[n] = mass[n] > 0 ? 1.0 / mass[n] : 0.0;
  const std::vector<double> before = mass;
  EXPECT_NEAR(node_stable_step(stiffness, mass), 0.25 * step, 1e-15 * step);

  const MassScaling r = scale_masses_to_step(stiffness, step, mass, inv_mass);
  EXPECT_EQ(r.scaled_nodes, 2u);
  EXPECT_EQ(r.largest_node, 3);
  EXPECT_NEAR(r.largest_factor, 16.0, 1e-13);
  EXPECT_NEAR(mass[0], 4.0 * before[0], 1e-15);
  EXPECT_EQ(mass[1], before[1]);  // exactly at the target: unchanged
  EXPECT_EQ(mass[2], before[2]);
  EXPECT_EQ(mass[4], 0.0);
  EXPECT_NEAR(r.added, 3.0 * before[0] + 15.0 * before[3], 1e-15);
  for (int n = 0; n < 4; ++n) EXPECT_EQ(inv_mass[n], 1.0 / mass[n]);
  EXPECT_NEAR(node_stable_step(stiffness, mass), step, 1e-15 * step);

  // A target at or below every node's step changes nothing.
  const std::vector<double> scaled = mass;
  const MassScaling none = scale_masses_to_step(stiffness, 0.5 * step, mass, inv_mass);
  EXPECT_EQ(none.scaled_nodes, 0u);
  EXPECT_EQ(none.added, 0.0);
  EXPECT_EQ(none.largest_node, -1);
  EXPECT_EQ(mass, scaled);
}

}  // namespace
}  // namespace rift::kernels
