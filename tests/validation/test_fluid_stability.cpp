// Stability at the extremes, fluid side (issue 7): the lid-driven cavity slab of test_fluid_cavity.cpp with
// water's density and viscosities from water (1e-3 Pa s, Re = 1e6 on an 8 x 8 grid: far beyond what the
// grid resolves) to the paper's very viscous fluid (1e5 Pa s, Re = 1e-2). Each must run with bounded
// energy while its steps converge: no NaN, |u| within 1.5 x the lid speed, kinetic energy below that of the
// whole slab moving at the lid speed (the lid is the only source of energy and the walls hold the fluid, so
// a bounded solution cannot exceed it; an unstable one does within a few steps). On the one-cell slab
// FGMRES on the Schur complement reaches its iteration cap from the second step on at every viscosity (its
// nodes all lie on the free-slip planes, so no node carries u_z, and the pressure modes that alternate
// between the two planes meet only the thin cell's shear, which the preconditioner's M/mu + (c + tau_p) K
// does not model). The step reports it, and a scene stops there with its diagnosis
// (fluid.on_picard_failure): what the solver returns after a step that did not converge is recorded, not
// asserted beyond being finite. It depends on the last bits of the unconverged iterations, so on the
// build's machine: at 1e1 Pa s it stayed within the bounds in earlier builds and reached 3.4 x the lid
// speed (kinetic energy 3.9 x the bound) from unconverged steps in a build on an AMD EPYC (-march=native).
// With two cells across (the same cavity 0.25 thick) every Picard iteration converges from water to 1e5 Pa s,
// and the bounds hold at every step, which the second test asserts. docs/stability.md.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/mesh/structured_box.hpp"
#include "systems/fluid/fluid_solver.hpp"
#include "tests/validation/fluid_cavity.hpp"

namespace rift {
namespace {

struct FluidOutcome {
  bool finite = true, converged = true;
  // Over the steps up to the first that did not converge, and over all steps.
  double max_speed = 0.0, max_kinetic = 0.0, bound_kinetic = 0.0;
  double max_speed_all = 0.0, max_kinetic_all = 0.0;
  int converged_steps = 0, max_picard = 0;
};

// layers: cells across the slab's thickness (each 1/8 thick, as the 8 x 8 cells in plane).
FluidOutcome run_viscous_cavity(double mu, fluid::PressureCoupling coupling, int layers = 1) {
  const int n = 8;
  StructuredBoxSpec spec;
  spec.hi = {1.0, 1.0, static_cast<double>(layers) / n};
  spec.cells = {n, n, layers};
  const TetMesh mesh = structured_box(spec);
  fluid::FluidSettings s;
  s.rho = 1000.0;
  s.mu = mu;
  s.dt = 0.08;  // lid CFL 0.6
  s.coupling = coupling;
  s.picard_max_iterations = 30;
  s.picard_tol = 1e-5;
  fluid::FluidSolver solver(mesh, s, fluid_test::cavity_boundaries());
  FluidOutcome out;
  double volume = 0.0;
  for (double v : solver.volumes()) volume += v;
  out.bound_kinetic = 0.5 * s.rho * volume;
  for (int step = 0; step < 20; ++step) {
    const fluid::FluidStepReport r = solver.step();
    out.converged = out.converged && r.converged;
    out.max_picard = std::max(out.max_picard, r.picard_iterations);
    const auto u = solver.velocity();
    const auto tets = solver.tets();
    double kinetic = 0.0;
    for (size_t t = 0; t < solver.volumes().size(); ++t) {
      double u2 = 0.0;
      for (int k = 0; k < 4; ++k)
        for (int d = 0; d < 3; ++d) u2 += 0.25 * u[3 * tets[4 * t + k] + d] * u[3 * tets[4 * t + k] + d];
      kinetic += 0.5 * s.rho * solver.volumes()[t] * u2;
    }
    double speed = 0.0;
    for (double v : u) {
      out.finite = out.finite && std::isfinite(v);
      speed = std::max(speed, std::abs(v));
    }
    out.max_speed_all = std::max(out.max_speed_all, speed);
    out.max_kinetic_all = std::max(out.max_kinetic_all, kinetic);
    if (out.converged) {
      ++out.converged_steps;
      out.max_speed = std::max(out.max_speed, speed);
      out.max_kinetic = std::max(out.max_kinetic, kinetic);
    }
    for (double p : solver.pressure()) out.finite = out.finite && std::isfinite(p);
    if (!out.finite) break;
  }
  return out;
}

class FluidViscosityRange : public testing::TestWithParam<double> {};

TEST_P(FluidViscosityRange, CavityRunsWithBoundedEnergy) {
  const double mu = GetParam();
  const FluidOutcome o = run_viscous_cavity(mu, fluid::PressureCoupling::schur_gmres);
  RecordProperty("max_speed_all_steps", testing::PrintToString(o.max_speed_all));
  RecordProperty("kinetic_over_bound_all_steps", testing::PrintToString(o.max_kinetic_all / o.bound_kinetic));
  RecordProperty("converged_steps", testing::PrintToString(o.converged_steps));
  RecordProperty("max_picard", testing::PrintToString(o.max_picard));
  RecordProperty("picard_converged", o.converged ? "yes" : "no");
  EXPECT_TRUE(o.finite);
  EXPECT_GE(o.converged_steps, 1);
  EXPECT_LE(o.max_speed, 1.5);
  EXPECT_LT(o.max_kinetic, o.bound_kinetic);
}

// Two cells across: the moving cavity's every Picard iteration converges (FGMRES on the Schur complement
// within its cap), water to the paper's fluid.
TEST_P(FluidViscosityRange, EveryStepConvergesWithTwoCellsAcross) {
  const FluidOutcome o = run_viscous_cavity(GetParam(), fluid::PressureCoupling::schur_gmres, 2);
  RecordProperty("max_picard", testing::PrintToString(o.max_picard));
  EXPECT_TRUE(o.finite);
  EXPECT_TRUE(o.converged);
  EXPECT_LE(o.max_speed, 1.5);
  EXPECT_LT(o.max_kinetic, o.bound_kinetic);
}

INSTANTIATE_TEST_SUITE_P(WaterToThePapersFluid, FluidViscosityRange,
                         testing::Values(1e-3, 1e-1, 1e1, 1e3, 1e5));

}  // namespace
}  // namespace rift
