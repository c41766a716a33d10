#pragma once
// Lid-driven cavity at Re = 100, 400 or 1000 against Ghia, Ghia & Shin (1982) (fluid.md 4.1), shared by
// tests/validation/test_fluid_cavity.cpp and bench/bench_fluid.cpp: the unit square as a thin slab (one
// cell thick) with free-slip z planes, lid u = 1 on ymax (the walls win at the two lid corners),
// mu = 1/Re, rho = 1, backward Euler to steady state (per-step change < 1e-6 dt). Centre-line velocities
// are read on grid lines (P1 is linear along the cell edges there) and compared with the table at its 15
// interior points.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <utility>
#include <vector>

#include "tests/validation/fluid_support.hpp"
#include "tests/validation/ghia1982.hpp"

namespace rift::fluid_test {

using fluid::BoundaryKind;
using fluid::FluidBoundary;
using fluid::FluidSettings;
using fluid::FluidSolver;
using fluid::Vec3;

struct CavityResult {
  double max_du = 0.0, max_dv = 0.0;
  double suspect_dv = 0.0;       // |dv| at the table's misprinted point (ghia1982.hpp), not in max_dv
  std::vector<double> velocity;  // the steady field, 3 per node
  int steps = 0;
  double change_per_time = 0.0;  // the last step's relative change / dt (steady: below steady_tol)
  size_t nodes = 0;
  // The time march alone (mesh and solver set-up excluded): wall and process CPU seconds.
  double march_seconds = 0.0, march_cpu_seconds = 0.0;
};

// How each step is solved. The steady state (what is compared with Ghia) is the fixed point of the
// projection iteration whatever these are; they set the cost per step and the number of steps. Default:
// one linearised projection step per time step (like icoFoam's one PISO predictor per step), the
// velocity predictor reduced by 0.1 and the pressure correction by 1e-3 (icoFoam: U to 1e-5, the first
// p corrector to relTol 0.05). With 3 Picard iterations, every inner solve to its full
// tolerance (velocity 1e-10, pressure 1e-8): the same Ghia errors to 4 digits, ~385 instead of ~710
// steps at 32^2, at several times the CPU time per step (docs/performance.md).
struct CavityOptions {
  int picard_iterations = 1;
  double velocity_forcing = 0.1;     // FluidSettings::velocity_forcing
  double projection_forcing = 1e-3;  // FluidSettings::projection_forcing
  int reynolds = 100;                // mu = 1 / reynolds
  bool supg = false;                 // the orthogonal-subscale convection stabilisation
  double steady_tol = 1e-6;          // per-step change below steady_tol dt (relative to max |u|)
  int max_steps = 100000;
  double picard_tol = 1e-6;  // FluidSettings::picard_tol
  // Node x_i = (1 - c) i/n + c (1 - cos(pi i/n)) / 2 along x and y: c = 0 uniform, larger c finer at the
  // walls (c = 0.5: the wall cells 0.4 x, the centre cells 1.6 x the uniform size).
  double wall_clustering = 0.0;
};

// The lattice coordinates along x and y of a cavity with n cells (CavityOptions::wall_clustering).
inline std::vector<double> cavity_axis(int n, double c) {
  std::vector<double> x(static_cast<size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double xi = static_cast<double>(i) / n;
    x[static_cast<size_t>(i)] = (1.0 - c) * xi + c * 0.5 * (1.0 - std::cos(std::acos(-1.0) * xi));
  }
  x.front() = 0.0;
  x.back() = 1.0;
  return x;
}

// The cell [ax[j], ax[j+1]] holding y and the fraction of it below y.
inline std::pair<int, double> cavity_axis_cell(const std::vector<double>& ax, double y) {
  const int n = static_cast<int>(ax.size()) - 1;
  int j = static_cast<int>(std::upper_bound(ax.begin(), ax.end(), y) - ax.begin()) - 1;
  j = std::clamp(j, 0, n - 1);
  return {j,
          (y - ax[static_cast<size_t>(j)]) / (ax[static_cast<size_t>(j) + 1] - ax[static_cast<size_t>(j)])};
}

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
  const std::vector<double> axis = cavity_axis(n, opt.wall_clustering);
  const TetMesh mesh = structured_box_on_axes({axis, axis, {0.0, 1.0 / n}});
  FluidSettings s;
  s.rho = 1.0;
  s.mu = 1.0 / opt.reynolds;
  s.dt = dt;
  s.supg = opt.supg;
  s.coupling = fluid::PressureCoupling::projection;
  s.picard_tol = opt.picard_tol;
  s.picard_max_iterations = opt.picard_iterations;
  s.velocity_forcing = opt.velocity_forcing;
  s.projection_forcing = opt.projection_forcing;
  FluidSolver solver(mesh, s, cavity_boundaries());
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  const auto steady = fluid_test::march_to_steady(solver, opt.steady_tol * s.dt, opt.max_steps);
  CavityResult r;
  r.march_cpu_seconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  r.march_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.steps = steady.steps;
  r.change_per_time = steady.change / dt;
  r.nodes = solver.node_count();
  const auto x = solver.nodes();
  const auto u = solver.velocity();
  // Node (i, j, 0) has index i + (n + 1) j.
  const auto at = [&](int i, int j, int d) { return u[3 * static_cast<size_t>(i + (n + 1) * j) + d]; };
  (void)x;
  const GhiaTable& ghia = ghia_table(opt.reynolds);
  r.velocity.assign(u.begin(), u.end());
  for (int k = 0; k < 17; ++k) {
    const auto [j, a] = cavity_axis_cell(axis, kGhiaY[k]);
    const double uh = (1 - a) * at(n / 2, j, 0) + a * at(n / 2, j + 1, 0);
    if (k > 0 && k < 16) r.max_du = std::max(r.max_du, std::abs(uh - ghia.u[k]));
    const auto [i, b] = cavity_axis_cell(axis, kGhiaX[k]);
    const double vh = (1 - b) * at(i, n / 2, 1) + b * at(i + 1, n / 2, 1);
    if (k == ghia.suspect_v)
      r.suspect_dv = std::abs(vh - ghia.v[k]);
    else if (k > 0 && k < 16)
      r.max_dv = std::max(r.max_dv, std::abs(vh - ghia.v[k]));
  }
  std::printf(
      "cavity Re %d n = %d, dt = %.3f, supg %d: max |du| %.4f, max |dv| %.4f, %d steps; last step %d Picard, "
      "%d FGMRES, %d BiCGSTAB, %d PCG, cfl %.2f, change/dt %.1e\n",
      opt.reynolds, n, dt, opt.supg ? 1 : 0, r.max_du, r.max_dv, r.steps, steady.last.picard_iterations,
      steady.last.schur_iterations, steady.last.velocity_iterations, steady.last.pressure_iterations,
      steady.last.cfl, r.change_per_time);
  return r;
}

}  // namespace rift::fluid_test
