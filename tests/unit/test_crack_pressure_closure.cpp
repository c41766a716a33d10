// The implicit closure of the fluid spring (kernels/crack_pressure_closure.hpp) on a piston: one crack
// triangle whose six corner nodes are held by springs (the rock's stand-in) and filled with water. The
// step is 1.8x beyond the explicit limit of the fluid spring: taken explicitly it blows up; with the
// closure the piston settles on the equilibrium that the equation of state and the springs give together, to
// 1e-9 (rounding over 4000 damped steps).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernels/crack_pressure_closure.hpp"
#include "kernels/fracture_flow.hpp"
#include "systems/fracture_flow/network_flow.hpp"

namespace rift {
namespace {

const kernels::FluidEos kWater{1000.0, 0.0, 2.2e9};

struct Piston {
  static constexpr double L = 0.01, w0 = 2e-6, k = 1e9, m = 1e-3, c = 2e5;
  std::vector<double> x, v, rest, area_vector, inv_mass;
  std::vector<int32_t> vertex{0, 1, 2, 0, 1, 2}, corners{0, 1, 2, 3, 4, 5}, triangle{0, 1, 2};
  std::vector<int32_t> node{0, 1, 2, 3, 4, 5};
  std::vector<uint8_t> free_mask = std::vector<uint8_t>(18, 1);
  double area = 0.5 * L * L;
  Piston() {
    const double xy[3][2] = {{0, 0}, {L, 0}, {0, L}};
    for (int side = 0; side < 2; ++side)
      for (auto& p : xy) x.insert(x.end(), {p[0], p[1], side == 0 ? w0 : 0.0});
    rest = x;
    v.assign(18, 0.0);
    inv_mass.assign(6, 1.0 / m);
    area_vector.assign(18, 0.0);
    const double n[3] = {0, 0, 1};
    // Entry i is corner i of the one triangle.
    const std::vector<int32_t> start{0, 1, 2, 3, 4, 5, 6};
    const double opening[3] = {w0, w0, w0};
    std::vector<double> open_area_vector(18);
    kernels::gather_area_vectors(start, corners, n, std::span<const double>(&area, 1), opening, 0.0,
                                 area_vector, open_area_vector, 0, 6);
  }
  kernels::CrackClosureNodes nodes() const { return {node, vertex, area_vector, inv_mass, free_mask}; }
  // Springs, the pressure p on the faces, and one damped leapfrog step.
  void explicit_step(double dt, std::span<const double> p) {
    const double g = 1.0 / (1.0 + c * dt / 2.0);
    for (size_t n = 0; n < 6; ++n)
      for (size_t d = 0; d < 3; ++d) {
        const double f =
            -k * (x[3 * n + d] - rest[3 * n + d]) + p[size_t(vertex[n])] * area_vector[3 * n + d];
        v[3 * n + d] = ((1.0 - c * dt / 2.0) * v[3 * n + d] + dt * f / m) * g;
        x[3 * n + d] += dt * v[3 * n + d];
      }
  }
  // The lumped volumes A w_k / 3 of the crack triangle.
  std::vector<double> volumes() const {
    const double* c6[6];
    for (int i = 0; i < 6; ++i) c6[i] = &x[3 * size_t(i)];
    const kernels::CrackTriangle t = kernels::crack_triangle(c6);
    return {t.area * t.opening[0] / 3.0, t.area * t.opening[1] / 3.0, t.area * t.opening[2] / 3.0};
  }
};

// Runs the piston for `steps`; returns the final pressure, or NaN once it has blown up.
double run_piston(Piston& pz, double dt, int steps, bool closure, double fluid_mass) {
  NetworkFlow flow(kWater, 0.0, -1e9);
  flow.set_network(pz.triangle, 3);
  std::vector<double> pressure(3, 0.0), mass(3, fluid_mass / 3.0), wet(3, 0.0), exchanged(3, 0.0);
  std::vector<uint8_t> role(3, uint8_t(FlowRole::wet));
  std::vector<double> applied(3, 0.0), source(3, 0.0), fixed(3, 0.0), tx(9), aperture(3, Piston::w0);
  NetworkFlowState st{pressure, mass, role, wet, exchanged};
  NetworkFlowBooks books;
  const double g = 1.0 / (1.0 + Piston::c * dt / 2.0);
  for (int s = 0; s < steps; ++s) {
    pz.explicit_step(dt, applied);
    std::vector<double> compliance(3, 0.0);
    if (closure) kernels::add_closure_compliance(pz.nodes(), dt, g, compliance);
    const std::vector<double> volume = pz.volumes();
    NetworkFlowStepInput in{dt, dt * (s + 1), tx, aperture, volume, compliance, applied, source, fixed};
    if (!flow.step(in, st, books).empty()) return std::nan("");
    std::vector<double> felt(6), now(6);
    for (size_t i = 0; i < 6; ++i) {
      felt[i] = applied[size_t(pz.vertex[i])];
      now[i] = pressure[size_t(pz.vertex[i])];
    }
    if (closure) kernels::apply_closure(pz.nodes(), dt, g, felt, now, pz.x, pz.v);
    applied = pressure;
    if (!std::isfinite(pressure[0]) || std::abs(pz.x[2] - Piston::w0) > 1.0) return std::nan("");
  }
  return pressure[0];
}

TEST(CrackPressureClosure, APistonBeyondTheFluidSpringsExplicitLimitSettlesOnItsEquilibrium) {
  Piston pz;
  const double V0 = pz.area * Piston::w0;
  const double fluid_mass = kWater.density(1e6) * V0;  // 1 MPa if the walls did not move
  // Explicit limits: the springs alone 2 sqrt(m / k) = 2e-6 s; with the fluid spring beside them,
  // 2 sqrt(m / (k + k_f)). In the piston's mode every corner moves delta away from the mid-plane, the
  // volume A (w0 + 2 delta) grows by 2 A delta, the pressure by K_f 2 A delta / V0, and each node's force
  // by A/3 of that: k_f = 2 K_f A / (3 w0), 37 times k.
  const double k_f = 2.0 * kWater.bulk_modulus * pz.area / (3.0 * Piston::w0);
  const double dt_fluid = 2.0 * std::sqrt(Piston::m / (Piston::k + k_f));
  const double dt = 1.8 * dt_fluid;
  ASSERT_LT(dt, 2.0 * std::sqrt(Piston::m / Piston::k));  // the solid's own step still holds
  // Equilibrium: each node's spring carries p A / 3, so w = w0 + 2 p A / (3 k) and V(p) = V0 + C p with
  // C = 2 A^2 / (3 k); rho(p) V(p) = the fluid's mass.
  const double p_eq =
      kernels::pressure_of_mass(kWater, fluid_mass, V0, 2.0 * pz.area * pz.area / (3.0 * Piston::k), 0.0);
  ASSERT_GT(p_eq, 1e4);
  ASSERT_LT(p_eq, 1e6);
  const double p = run_piston(pz, dt, 4000, true, fluid_mass);
  EXPECT_NEAR(p, p_eq, 1e-9 * p_eq);
  EXPECT_NEAR(pz.x[2] - Piston::w0, p_eq * pz.area / (3.0 * Piston::k), 1e-9 * Piston::w0);

  Piston explicit_pz;
  const double p_explicit = run_piston(explicit_pz, dt, 4000, false, fluid_mass);
  // (It ends near -K_f: the oscillation tears the crack open until the water's density nears zero.)
  EXPECT_FALSE(std::abs(p_explicit - p_eq) < 0.5 * p_eq)
      << p_explicit << ": the explicit fluid spring was expected to blow up at 1.8x its stable step";
  // Within its limit the explicit coupling reaches the same equilibrium (the closure changes the path,
  // not the answer).
  Piston slow_pz;
  EXPECT_NEAR(run_piston(slow_pz, 0.5 * dt_fluid, 15000, false, fluid_mass), p_eq, 1e-6 * p_eq);
}

}  // namespace
}  // namespace rift
