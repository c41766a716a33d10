// Fluid solver hooks and boundary conditions on small meshes (fluid.md 1.2-1.3, 4.6):
//  - absorption: a channel with free-slip walls driven by a pressure drop G L and a momentum source s has
//    the uniform Darcy-like solution sigma (u - u_s) = G + s, whatever the viscosity (the flow is uniform);
//  - hydrostatics: a closed box under gravity f = -rho g e_z keeps u = 0 and p = -rho g z + c exactly,
//    also with a sigma that jumps between the two halves (the penalty must not create spurious flow);
//  - the projection variant reaches the same steady Poiseuille-free plug flow as the Schur variant;
//  - bad input is refused with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/mesh/structured_box.hpp"
#include "systems/fluid/fluid_solver.hpp"

namespace rift::fluid {
namespace {

TetMesh channel() {
  StructuredBoxSpec spec;
  spec.hi = {2.0, 1.0, 1.0};
  spec.cells = {6, 3, 3};
  return structured_box(spec);
}

std::vector<FluidBoundary> plug_bcs(double p_in) {
  return {{"xmin", BoundaryKind::pressure, {}, [=](const Vec3&, double) { return p_in; }},
          {"xmax", BoundaryKind::outflow, {}, {}},
          {"ymin", BoundaryKind::free_slip, {}, {}},
          {"ymax", BoundaryKind::free_slip, {}, {}},
          {"zmin", BoundaryKind::free_slip, {}, {}},
          {"zmax", BoundaryKind::free_slip, {}, {}}};
}

void expect_uniform(const FluidSolver& s, const Vec3& u_expect, double tol) {
  const auto u = s.velocity();
  for (size_t n = 0; n < s.node_count(); ++n)
    for (int d = 0; d < 3; ++d) ASSERT_NEAR(u[3 * n + d], u_expect[d], tol) << "node " << n << " comp " << d;
}

TEST(FluidSolver, AbsorptionTargetAndSourceGiveTheDarcySolution) {
  for (const PressureCoupling coupling : {PressureCoupling::schur_gmres, PressureCoupling::projection}) {
    FluidSettings st;
    st.rho = 1000.0;
    st.mu = 10.0;
    st.dt = 1.0;
    st.coupling = coupling;
    st.picard_max_iterations = 50;
    st.picard_tol = 1e-10;
    const double g = 3.0, sigma = 2000.0, us = 0.25, src = 1.0;  // G = 6 Pa / 2 m
    FluidSolver s(channel(), st, plug_bcs(g * 2.0));
    for (double& v : s.sigma()) v = sigma;
    for (size_t t = 0; t < s.sigma().size(); ++t) {
      s.target_velocity()[3 * t] = us;
      s.source()[3 * t] = src;
    }
    s.absorption_changed();
    FluidStepReport rep;
    for (int i = 0; i < 40; ++i) rep = s.step();
    SCOPED_TRACE(coupling == PressureCoupling::projection ? "projection" : "schur_gmres");
    std::printf("last step: %d Picard, du %.2e, %d FGMRES, %d BiCGSTAB, %d PCG\n", rep.picard_iterations,
                rep.velocity_change, rep.schur_iterations, rep.velocity_iterations, rep.pressure_iterations);
    EXPECT_TRUE(rep.converged);
    expect_uniform(s, {us + (g + src) / sigma, 0.0, 0.0}, 1e-9);
    EXPECT_LT(rep.divergence_max, 1e-8);
    // Pressure: linear from 6 to 0.
    const auto p = s.pressure();
    const auto x = s.nodes();
    for (size_t n = 0; n < s.node_count(); ++n) EXPECT_NEAR(p[n], g * (2.0 - x[3 * n]), 1e-8);
  }
}

// A pressure that ramps in time (the paper's 15 MPa then 2e4 MPa/s, scaled): the uniform flow obeys
// rho du/dt + sigma u = G(t), and backward Euler gives exactly
// u^{n+1} = (rho/dt u^n + G(t^{n+1})) / (rho/dt + sigma) at every node.
TEST(FluidSolver, PressureRampDrivesTheDiscreteDarcyRecursion) {
  FluidSettings st;
  st.rho = 1000.0;
  st.mu = 1e5;
  st.dt = 1e-3;
  st.picard_tol = 1e-12;
  const double sigma = 5e5;
  const auto p_in = [](double t) { return 15.0 + 2e4 * t; };
  std::vector<FluidBoundary> bcs = plug_bcs(0.0);
  bcs[0].pressure = [&](const Vec3&, double t) { return p_in(t); };
  FluidSolver s(channel(), st, bcs);
  for (double& v : s.sigma()) v = sigma;
  s.absorption_changed();
  double u = 0.0;
  for (int i = 0; i < 5; ++i) {
    const FluidStepReport rep = s.step();
    EXPECT_TRUE(rep.converged);
    u = (st.rho / st.dt * u + p_in(s.time()) / 2.0) / (st.rho / st.dt + sigma);
    expect_uniform(s, {u, 0.0, 0.0}, 1e-7 * std::abs(u));  // FGMRES to 1e-8
  }
}

TEST(FluidSolver, HydrostaticBoxStaysAtRestWithAJumpInSigma) {
  StructuredBoxSpec spec;
  spec.cells = {4, 4, 4};
  const TetMesh mesh = structured_box(spec);
  FluidSettings st;
  st.rho = 1000.0;
  st.mu = 1e-3;
  st.dt = 0.01;
  std::vector<FluidBoundary> walls;
  for (const char* f : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
    walls.push_back({f, BoundaryKind::no_slip, {}, {}});
  FluidSolver s(mesh, st, walls);
  const double g = 9.81;
  s.set_body_force([=](const Vec3&, double) { return Vec3{0.0, 0.0, -1000.0 * g}; });
  const auto tets = s.tets();
  const auto x = s.nodes();
  for (size_t t = 0; t < s.sigma().size(); ++t) {
    double cx = 0.0;
    for (int a = 0; a < 4; ++a) cx += 0.25 * x[3 * static_cast<size_t>(tets[4 * t + a])];
    s.sigma()[t] = cx < 0.5 ? 1e6 : 0.0;
  }
  s.absorption_changed();
  FluidStepReport rep;
  for (int i = 0; i < 3; ++i) rep = s.step();
  double umax = 0.0;
  for (double v : s.velocity()) umax = std::max(umax, std::abs(v));
  // One step of unbalanced gravity would give g dt ~ 0.1 m/s; what is left is solver tolerance (2.7e-9
  // in the -O1 sanitizer build, 1e-10 at -O2).
  EXPECT_LT(umax, 1e-8);
  const auto p = s.pressure();
  for (size_t n = 0; n < s.node_count(); ++n) EXPECT_NEAR(p[n], -1000.0 * g * (x[3 * n + 2] - 0.5), 1e-6);
  EXPECT_EQ(rep.cfl, rep.cfl);
}

TEST(FluidSolver, RefusesBadInput) {
  FluidSettings st;
  EXPECT_THROW(FluidSolver(channel(), st, {{"nowhere", BoundaryKind::no_slip, {}, {}}}),
               std::invalid_argument);
  EXPECT_THROW(FluidSolver(channel(), st, {{"xmin", BoundaryKind::velocity, {}, {}}}), std::invalid_argument);
  st.theta = 0.2;
  EXPECT_THROW(FluidSolver(channel(), st, {}), std::invalid_argument);
}

}  // namespace
}  // namespace rift::fluid
