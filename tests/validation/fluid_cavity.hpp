#pragma once
// Lid-driven cavity at Re = 100 against Ghia, Ghia & Shin (1982) (fluid.md 4.1), shared by
// tests/validation/test_fluid_cavity.cpp and bench/bench_fluid.cpp: the unit square as a thin slab (one
// cell thick) with free-slip z planes, lid u = 1 on ymax (the walls win at the two lid corners),
// mu = 0.01, rho = 1, backward Euler to steady state (per-step change < 1e-6 dt). Centre-line velocities
// are read on grid lines (P1 is linear along the cell edges there) and compared with the table at its 15
// interior points.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "tests/validation/fluid_support.hpp"

namespace rift::fluid_test {

using fluid::BoundaryKind;
using fluid::FluidBoundary;
using fluid::FluidSettings;
using fluid::FluidSolver;
using fluid::Vec3;

inline constexpr double kGhiaY[17] = {1.0,    0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5,
                                      0.4531, 0.2813, 0.1719, 0.1016, 0.0703, 0.0625, 0.0547, 0.0};
inline constexpr double kGhiaU[17] = {1.0,      0.84123,  0.78871,  0.73722,  0.68717,  0.23151,
                                      0.00332,  -0.13641, -0.20581, -0.2109,  -0.15662, -0.1015,
                                      -0.06434, -0.04775, -0.04192, -0.03717, 0.0};
inline constexpr double kGhiaX[17] = {1.0,    0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5,
                                      0.2344, 0.2266, 0.1563, 0.0938, 0.0781, 0.0703, 0.0625, 0.0};
inline constexpr double kGhiaV[17] = {0.0,      -0.05906, -0.07391, -0.08864, -0.10313, -0.16914,
                                      -0.22445, -0.24533, 0.05454,  0.17527,  0.17507,  0.16077,
                                      0.12317,  0.1089,   0.10091,  0.09233,  0.0};

struct CavityResult {
  double max_du = 0.0, max_dv = 0.0;
  int steps = 0;
  size_t nodes = 0;
  // The time march alone (mesh and solver set-up excluded): wall and process CPU seconds.
  double march_seconds = 0.0, march_cpu_seconds = 0.0;
};

// How each step is solved. The steady state (what is compared with Ghia) is the fixed point of the
// projection iteration whatever these are; they set the cost per step and the number of steps. Default:
// one linearised projection step per time step (like icoFoam's one PISO predictor per step), the
// velocity predictor reduced by 0.1 and the pressure correction by 1e-3 (icoFoam: U to 1e-5, the first
// p corrector to relTol 0.05). Until this change: 3 Picard iterations, every inner solve to its full
// tolerance (velocity 1e-10, pressure 1e-8): the same Ghia errors to 4 digits, ~385 instead of ~710
// steps at 32^2, at several times the CPU time per step (docs/performance.md).
struct CavityOptions {
  int picard_iterations = 1;
  double velocity_forcing = 0.1;     // FluidSettings::velocity_forcing
  double projection_forcing = 1e-3;  // FluidSettings::projection_forcing
};

// Lid u = 1 on ymax, no slip on the other walls, free slip on the slab's z planes.
inline std::vector<FluidBoundary> cavity_boundaries() {
  return {{"ymax",
           BoundaryKind::velocity,
           [](const Vec3&, double) {
             return Vec3{1, 0, 0};
           },
           {}},
          {"xmin", BoundaryKind::no_slip, {}, {}},
          {"xmax", BoundaryKind::no_slip, {}, {}},
          {"ymin", BoundaryKind::no_slip, {}, {}},
          {"zmin", BoundaryKind::free_slip, {}, {}},
          {"zmax", BoundaryKind::free_slip, {}, {}}};
}

inline CavityResult run_cavity(int n, double dt, CavityOptions opt = {}) {
  StructuredBoxSpec spec;
  spec.hi = {1.0, 1.0, 1.0 / n};
  spec.cells = {n, n, 1};
  const TetMesh mesh = structured_box(spec);
  FluidSettings s;
  s.rho = 1.0;
  s.mu = 0.01;
  s.dt = dt;
  s.supg = false;  // the cell Peclet number U h / nu is 6 at n = 16: Galerkin is still fine, and consistent
  s.coupling = fluid::PressureCoupling::projection;
  s.picard_tol = 1e-6;
  s.picard_max_iterations = opt.picard_iterations;
  s.velocity_forcing = opt.velocity_forcing;
  s.projection_forcing = opt.projection_forcing;
  FluidSolver solver(mesh, s, cavity_boundaries());
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  const auto steady = fluid_test::march_to_steady(solver, 1e-6 * s.dt, 100000);
  CavityResult r;
  r.march_cpu_seconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  r.march_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.steps = steady.steps;
  r.nodes = solver.node_count();
  const auto x = solver.nodes();
  const auto u = solver.velocity();
  // Node (i, j, 0) has index i + (n + 1) j.
  const auto at = [&](int i, int j, int d) { return u[3 * static_cast<size_t>(i + (n + 1) * j) + d]; };
  (void)x;
  for (int k = 0; k < 17; ++k) {
    const double fy = kGhiaY[k] * n;
    const int j = std::min(static_cast<int>(fy), n - 1);
    const double a = fy - j;
    const double uh = (1 - a) * at(n / 2, j, 0) + a * at(n / 2, j + 1, 0);
    if (k > 0 && k < 16) r.max_du = std::max(r.max_du, std::abs(uh - kGhiaU[k]));
    const double fx = kGhiaX[k] * n;
    const int i = std::min(static_cast<int>(fx), n - 1);
    const double b = fx - i;
    const double vh = (1 - b) * at(i, n / 2, 1) + b * at(i + 1, n / 2, 1);
    if (k > 0 && k < 16) r.max_dv = std::max(r.max_dv, std::abs(vh - kGhiaV[k]));
  }
  std::printf(
      "cavity n = %d, dt = %.2f: max |du| %.4f, max |dv| %.4f, %d steps; last step %d Picard, %d FGMRES, "
      "%d BiCGSTAB, %d PCG, cfl %.2f\n",
      n, dt, r.max_du, r.max_dv, r.steps, steady.last.picard_iterations, steady.last.schur_iterations,
      steady.last.velocity_iterations, steady.last.pressure_iterations, steady.last.cfl);
  return r;
}

}  // namespace rift::fluid_test
