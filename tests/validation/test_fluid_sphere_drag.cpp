// Stokes drag on a sphere (issue 6, fluid.md 4.2): a sphere of radius R at rest in the concentric
// spherical container of radius b whose wall moves with the uniform velocity U e_x (the frame of a
// sphere translating at -U through fluid held at rest by the container). Creeping flow (no convection,
// dt so large that rho/dt is 1e-8 of mu/h^2: one steady Stokes solve). Exact drag (Cunningham 1910,
// Williams 1915; Happel & Brenner 1965, sec. 4-22), lambda = R / b:
//   F = 6 pi mu R U K,  K = (1 - lambda^5) / (1 - 9/4 lambda + 5/2 lambda^3 - 9/4 lambda^5 + lambda^6).
// Only a quarter is meshed (y >= 0, z >= 0) with free slip on the symmetry planes y = 0 and z = 0; the
// drag is 4 times the quarter's.
//
// Drag = the consistent reaction force on the sphere's no-slip nodes: the residual of the discrete
// x-momentum equation at those nodes, with the pressure term integrated by parts,
//   F_x = -sum_{i on sphere} sum_t V_t (mu grad u_x . grad N_i - p_t d N_i / dx),  p_t = cell mean,
// which equals int_sphere (sigma n)_x dS for the exact solution (at interior nodes it is the equation
// the solver solved, so it vanishes there) and converges at the rate of the energy norm squared, unlike
// the traction of the piecewise-constant P1 stress, which is O(h) on the surface. The SUPG and
// absorption terms are off, and the time term is rho/dt (u - u^n) ~ 1e-8: they add nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "engine/mesh/sphere_shell_generator.hpp"
#include "kernels/fluid_element.hpp"
#include "systems/fluid/fluid_solver.hpp"
#include "tests/validation/fluid_support.hpp"

namespace rift {
namespace {

using fluid::FluidSettings;
using fluid::FluidSolver;

TEST(FluidSphereDrag, StokesDragInASphericalContainer) {
  // Container correction check against the first-order wall effect K = 1 + 9/4 lambda.
  EXPECT_NEAR(fluid_test::container_correction(1e-4), 1 + 2.25e-4, 1e-7);
  constexpr double kR = 1.0, kB = 8.0, kMu = 1.0, kU = 1.0;
  SphereShellSpec spec;
  spec.radius = kR;
  spec.outer_radius = kB;
  // h = 0.08 R at the sphere, growing by 0.15 per unit distance. The far field matters: at grading 0.3
  // the error was +5.0 % (h 0.08), +4.5 % (h 0.05); at 0.15 +1.9 %, at 0.08 +0.8 % (56k tets, 13 s).
  spec.size_min = 0.08;
  spec.size_max = 2.0;
  spec.grading = 0.15;
  const auto t0 = std::chrono::steady_clock::now();
  const TetMesh mesh = generate_sphere_shell_mesh(spec);
  const auto t1 = std::chrono::steady_clock::now();

  const FluidSettings s = fluid_test::stokes_container_settings(kMu);
  const auto bcs = fluid_test::stokes_container_boundaries(kU);
  FluidSolver solver(mesh, s, bcs);
  const fluid::FluidStepReport rep = solver.step();
  const auto t2 = std::chrono::steady_clock::now();

  // The force on the sphere: the consistent reaction at its nodes (fluid_support.hpp).
  const size_t nn = solver.node_count();
  const auto tets = solver.tets();
  const size_t nt = tets.size() / 4;
  const auto vol = solver.volumes();
  const double drag = 4.0 * fluid_test::wall_force_x(mesh, solver, kMu, "sphere");
  // The mesh fills the quarter shell, inscribed in it: Mesh_3 keeps boundary triangles within 0.1 h of
  // the (faceted) spheres (facet_distance), so the volume falls short by at most 3 * 0.1 h_b / b
  // (h_b = 1.13 at the outer sphere: 4.2 %; 1.2 % measured). A container 1.2 % / 3 smaller in radius
  // raises K by 0.1 %.
  double volume = 0.0;
  for (double v : vol) volume += v;
  const double shell = std::numbers::pi / 3 * (kB * kB * kB - kR * kR * kR);
  const double h_outer = std::min(spec.size_max, spec.size_min + spec.grading * (kB - kR));
  EXPECT_LE(volume / shell, 1.0 + 1e-12);
  EXPECT_GE(volume / shell, 1.0 - 0.3 * h_outer / kB);
  const double k = fluid_test::container_correction(kR / kB);
  const double exact = 6 * std::numbers::pi * kMu * kR * kU * k;
  const double err = drag / exact - 1.0;
  std::printf(
      "sphere drag: %zu nodes, %zu tets, mesh %.1f s, solve %.1f s; Picard %d, FGMRES %d, BiCGSTAB %d, PCG "
      "%d; volume / exact %.5f; K = %.4f, F = %.4f, exact %.4f, error %+.2f %%; div max %.2e\n",
      nn, nt, std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count(),
      rep.picard_iterations, rep.schur_iterations, rep.velocity_iterations, rep.pressure_iterations,
      volume / shell, k, drag, exact, 100 * err, rep.divergence_max);
  // 5 % (issue 6): the discretisation error at this resolution; the container formula is exact for the
  // concentric geometry and the faceted spheres are within 3.4e-4 R of the true ones.
  EXPECT_LE(std::abs(err), 0.05);
  EXPECT_TRUE(rep.converged);
}

}  // namespace
}  // namespace rift
