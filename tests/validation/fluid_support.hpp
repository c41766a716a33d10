#pragma once
// Shared by the fluid validation tests: structured or jittered box meshes, time-marching to steady
// state, and L2 errors by quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "engine/mesh/structured_box.hpp"
#include "kernels/fluid_element.hpp"
#include "systems/fluid/fluid_solver.hpp"

namespace rift::fluid_test {

using fluid::Vec3;

// Structured box whose interior nodes are moved by up to jitter * (cell size) in each direction (a
// deterministic pseudo-random perturbation), so the tets are irregular and P1 is no longer nodally exact.
inline TetMesh jittered_box(const StructuredBoxSpec& spec, double jitter, unsigned seed = 7) {
  TetMesh m = structured_box(spec);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& p : m.nodes) {
    bool interior = true;
    for (int d = 0; d < 3; ++d) interior = interior && p[d] > spec.lo[d] && p[d] < spec.hi[d];
    for (int d = 0; d < 3; ++d) {
      const double r = u(rng);
      if (interior) p[d] += jitter * r * (spec.hi[d] - spec.lo[d]) / spec.cells[d];
    }
  }
  return m;
}

struct SteadyResult {
  int steps = 0;
  fluid::FluidStepReport last;
  double change = 0.0;  // the last step's max |u^{n+1} - u^n| / max |u|
};

// Steps until the step's velocity change (relative to max |u|) falls below tol.
inline SteadyResult march_to_steady(fluid::FluidSolver& s, double tol, int max_steps) {
  SteadyResult r;
  std::vector<double> prev(s.velocity().begin(), s.velocity().end());
  for (r.steps = 1; r.steps <= max_steps; ++r.steps) {
    r.last = s.step();
    double du = 0.0, um = 0.0;
    const auto u = s.velocity();
    for (size_t i = 0; i < u.size(); ++i) {
      du = std::max(du, std::abs(u[i] - prev[i]));
      um = std::max(um, std::abs(u[i]));
      prev[i] = u[i];
    }
    r.change = um > 0.0 ? du / um : du;
    if (du <= tol * um) break;
  }
  return r;
}

// sqrt(int |u_h - u|^2) and sqrt(int (p_h - pbar_h - (p - pbar))^2) with the degree-2 4-point rule.
struct L2Errors {
  double velocity = 0.0, pressure = 0.0, velocity_norm = 0.0;
};
template <class U, class P>
L2Errors l2_errors(const fluid::FluidSolver& s, U exact_u, P exact_p) {
  constexpr double a = 0.5854101966249685, b = 0.1381966011250105;
  const auto x = s.nodes();
  const auto tets = s.tets();
  const auto vol = s.volumes();
  const auto u = s.velocity();
  const auto p = s.pressure();
  const size_t nt = vol.size();
  // Means of p_h and p.
  double ph_mean = 0.0, p_mean = 0.0, vtot = 0.0;
  L2Errors e;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t t = 0; t < nt; ++t) {
      for (int q = 0; q < 4; ++q) {
        double lam[4];
        for (int c = 0; c < 4; ++c) lam[c] = c == q ? a : b;
        Vec3 xq{0, 0, 0}, uh{0, 0, 0};
        double phq = 0.0;
        for (int c = 0; c < 4; ++c) {
          const size_t n = static_cast<size_t>(tets[4 * t + c]);
          for (int d = 0; d < 3; ++d) {
            xq[d] += lam[c] * x[3 * n + d];
            uh[d] += lam[c] * u[3 * n + d];
          }
          phq += lam[c] * p[n];
        }
        const double w = vol[t] / 4.0;
        const double pq = exact_p(xq);
        if (pass == 0) {
          ph_mean += w * phq;
          p_mean += w * pq;
          vtot += w;
        } else {
          const Vec3 ue = exact_u(xq);
          for (int d = 0; d < 3; ++d) {
            e.velocity += w * (uh[d] - ue[d]) * (uh[d] - ue[d]);
            e.velocity_norm += w * ue[d] * ue[d];
          }
          const double dp = (phq - ph_mean) - (pq - p_mean);
          e.pressure += w * dp * dp;
        }
      }
    }
    if (pass == 0) {
      ph_mean /= vtot;
      p_mean /= vtot;
    }
  }
  e.velocity = std::sqrt(e.velocity);
  e.pressure = std::sqrt(e.pressure);
  e.velocity_norm = std::sqrt(e.velocity_norm);
  return e;
}

// The x force of the fluid on the no-slip wall `surface`: minus the consistent reaction at its nodes, the
// residual of the x-momentum equation there with the pressure term integrated by parts,
//   F_x = sum_{i on the wall} sum_t V_t (p_t dN_i/dx - mu grad u_x . grad N_i),   p_t = the cell mean,
// which equals int (sigma n)_x dS for the exact solution and converges at the rate of the energy norm
// squared (the traction of the piecewise-constant P1 stress is only O(h)). Valid where the time,
// convection, stabilisation and absorption terms vanish at the wall (a steady Stokes flow, u = 0 there).
inline double wall_force_x(const TetMesh& mesh, const fluid::FluidSolver& solver, double mu,
                           const std::string& surface) {
  const size_t nn = solver.node_count();
  const int32_t wall = mesh.surface_index(surface);
  std::vector<uint8_t> on_wall(nn, 0);
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    if (mesh.triangle_surface[f] == wall)
      for (int32_t v : mesh.triangles[f]) on_wall[v] = 1;
  const auto tets = solver.tets();
  const size_t nt = tets.size() / 4;
  std::vector<double> vol(nt), grad(12 * nt), h(nt);
  kernels::p1_prepare(solver.nodes(), tets, vol, grad, h);
  const auto u = solver.velocity();
  const auto p = solver.pressure();
  double reaction = 0.0;
  for (size_t t = 0; t < nt; ++t) {
    const double* g = &grad[12 * t];
    double gux[3] = {0, 0, 0}, pbar = 0.0;
    for (int a = 0; a < 4; ++a) {
      const size_t n = static_cast<size_t>(tets[4 * t + a]);
      for (int d = 0; d < 3; ++d) gux[d] += u[3 * n] * g[3 * a + d];
      pbar += 0.25 * p[n];
    }
    for (int a = 0; a < 4; ++a)
      if (on_wall[tets[4 * t + a]])
        reaction += vol[t] * (mu * (gux[0] * g[3 * a] + gux[1] * g[3 * a + 1] + gux[2] * g[3 * a + 2]) -
                              pbar * g[3 * a]);
  }
  return -reaction;
}

// Stokes' problem of a sphere in a concentric spherical container (the quarter of it meshed by
// generate_sphere_shell_mesh: free slip on y = 0 and z = 0, the "sphere" held, the "outer" wall moving at
// U e_x): creeping flow solved in one step (rho / dt = 1e-8 mu / h^2), and the exact drag's container
// correction K(lambda = R / b) (Cunningham 1910, Williams 1915; Happel & Brenner 1965, sec. 4-22), with
// F = 6 pi mu R U K.
inline fluid::FluidSettings stokes_container_settings(double mu) {
  fluid::FluidSettings s;
  s.rho = 1.0;
  s.mu = mu;
  s.dt = 1e8;
  s.convection = false;
  s.supg = false;
  s.picard_max_iterations = 2;
  s.picard_tol = 1e-6;
  return s;
}
inline std::vector<fluid::FluidBoundary> stokes_container_boundaries(double speed) {
  using fluid::BoundaryKind;
  return {{"ymin", BoundaryKind::free_slip, {}, {}},
          {"zmin", BoundaryKind::free_slip, {}, {}},
          {"sphere", BoundaryKind::no_slip, {}, {}},
          {"outer",
           BoundaryKind::velocity,
           [speed](const fluid::Vec3&, double) {
             return fluid::Vec3{speed, 0, 0};
           },
           {}}};
}
inline double container_correction(double lambda) {
  const double l3 = lambda * lambda * lambda, l5 = l3 * lambda * lambda, l6 = l5 * lambda;
  return (1 - l5) / (1 - 2.25 * lambda + 2.5 * l3 - 2.25 * l5 + l6);
}

}  // namespace rift::fluid_test
