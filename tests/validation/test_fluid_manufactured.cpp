// Manufactured solutions for the fluid solver (docs/fluid.md):
//  1. space: steady Stokes on the unit cube with u = (sin pi y sin pi z, sin pi x sin pi z, sin pi x sin pi
//  y)
//     (divergence free, -lap u = 2 pi^2 u), p = cos pi x cos pi y cos pi z, f = 2 pi^2 mu u + grad p,
//     u given on all faces (closed box: p up to a constant, compared after removing the means). Structured
//     meshes with 4, 8, 16 cells a side: P1 velocity converges at order 2 in L2, the pressure at >= 1
//     (1.5 is typical for the projection-stabilised P1-P1 pair on regular meshes).
//  2. time: unsteady Navier-Stokes with u = sin(t) (y, z, x), p = 0, f = rho (cos t (y, z, x) +
//     sin^2 t (z, x, y)). u is linear in space, which P1 represents exactly, so the error at t = 1 is the
//     time error alone: Crank-Nicolson quarters it when dt halves (order 2), backward Euler halves
//     it (order 1). Streamline diffusion is off (it is not consistent for this exact solution).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "tests/validation/fluid_support.hpp"

namespace rift {
namespace {

using fluid::BoundaryKind;
using fluid::FluidBoundary;
using fluid::FluidSettings;
using fluid::FluidSolver;
using fluid::Vec3;

constexpr double kPi = std::numbers::pi;

Vec3 stokes_u(const Vec3& x) {
  const double sx = std::sin(kPi * x[0]), sy = std::sin(kPi * x[1]), sz = std::sin(kPi * x[2]);
  return {sy * sz, sx * sz, sx * sy};
}
double stokes_p(const Vec3& x) {
  return std::cos(kPi * x[0]) * std::cos(kPi * x[1]) * std::cos(kPi * x[2]);
}

std::vector<FluidBoundary> all_velocity(const fluid::VectorField& g) {
  std::vector<FluidBoundary> bcs;
  for (const char* f : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
    bcs.push_back({f, BoundaryKind::velocity, g, {}});
  return bcs;
}

fluid_test::L2Errors stokes_errors(int n) {
  StructuredBoxSpec spec;
  spec.cells = {n, n, n};
  const TetMesh mesh = structured_box(spec);
  FluidSettings s;
  s.rho = 1.0;
  s.mu = 1.0;
  s.dt = 1e4;  // one backward-Euler step this long is the steady state
  s.convection = false;
  s.picard_max_iterations = 2;
  FluidSolver solver(mesh, s, all_velocity([](const Vec3& x, double) { return stokes_u(x); }));
  solver.set_body_force([&](const Vec3& x, double) {
    const Vec3 u = stokes_u(x);
    const double cx = std::cos(kPi * x[0]), cy = std::cos(kPi * x[1]), cz = std::cos(kPi * x[2]);
    const double sx = std::sin(kPi * x[0]), sy = std::sin(kPi * x[1]), sz = std::sin(kPi * x[2]);
    const Vec3 gp{-kPi * sx * cy * cz, -kPi * cx * sy * cz, -kPi * cx * cy * sz};
    return Vec3{2 * kPi * kPi * u[0] + gp[0], 2 * kPi * kPi * u[1] + gp[1], 2 * kPi * kPi * u[2] + gp[2]};
  });
  const auto rep = solver.step();
  std::printf("  n = %2d: %d Picard, %d FGMRES, %d BiCGSTAB, %d AMG-PCG its; div_l2 %.2e\n", n,
              rep.picard_iterations, rep.schur_iterations, rep.velocity_iterations, rep.pressure_iterations,
              rep.divergence_l2);
  return fluid_test::l2_errors(solver, stokes_u, stokes_p);
}

TEST(FluidManufactured, StokesSpatialOrder) {
  const int ns[3] = {4, 8, 16};
  fluid_test::L2Errors e[3];
  for (int i = 0; i < 3; ++i) e[i] = stokes_errors(ns[i]);
  for (int i = 0; i < 3; ++i)
    std::printf("n = %2d: |u - u_h| = %.4e (rel %.3e), |p - p_h| = %.4e\n", ns[i], e[i].velocity,
                e[i].velocity / e[i].velocity_norm, e[i].pressure);
  for (int i = 1; i < 3; ++i) {
    const double ou = std::log2(e[i - 1].velocity / e[i].velocity);
    const double op = std::log2(e[i - 1].pressure / e[i].pressure);
    std::printf("order %d -> %d: velocity %.2f, pressure %.2f\n", ns[i - 1], ns[i], ou, op);
    if (i == 2) {
      EXPECT_GT(ou, 1.8);
      EXPECT_GT(op, 1.0);
    }
  }
}

double time_error(double theta, double dt) {
  StructuredBoxSpec spec;
  spec.cells = {3, 3, 3};
  const TetMesh mesh = structured_box(spec);
  FluidSettings s;
  s.rho = 1.0;
  s.mu = 0.1;
  s.dt = dt;
  s.theta = theta;
  s.supg = false;
  s.picard_tol = 1e-12;
  s.picard_max_iterations = 30;
  const auto exact = [](const Vec3& x, double t) {
    const double a = std::sin(t);
    return Vec3{a * x[1], a * x[2], a * x[0]};
  };
  FluidSolver solver(mesh, s, all_velocity(exact));
  solver.set_body_force([](const Vec3& x, double t) {
    const double c = std::cos(t), s2 = std::sin(t) * std::sin(t);
    return Vec3{c * x[1] + s2 * x[2], c * x[2] + s2 * x[0], c * x[0] + s2 * x[1]};
  });
  solver.set_velocity([&](const Vec3& x, double) { return exact(x, 0.0); });
  const int steps = static_cast<int>(std::lround(1.0 / dt));
  for (int i = 0; i < steps; ++i) {
    const auto rep = solver.step();
    EXPECT_TRUE(rep.converged);
  }
  double err = 0.0;
  const auto u = solver.velocity();
  const auto x = solver.nodes();
  for (size_t n = 0; n < solver.node_count(); ++n) {
    const Vec3 ue = exact({x[3 * n], x[3 * n + 1], x[3 * n + 2]}, solver.time());
    for (int d = 0; d < 3; ++d) err = std::max(err, std::abs(u[3 * n + d] - ue[d]));
  }
  return err;
}

TEST(FluidManufactured, CrankNicolsonIsSecondOrderInTime) {
  const double dts[3] = {0.2, 0.1, 0.05};
  double cn[3], be[3];
  for (int i = 0; i < 3; ++i) {
    cn[i] = time_error(0.5, dts[i]);
    be[i] = time_error(1.0, dts[i]);
    std::printf("dt = %.3f: max error at t = 1: Crank-Nicolson %.3e, backward Euler %.3e\n", dts[i], cn[i],
                be[i]);
  }
  const double ocn = std::log2(cn[1] / cn[2]), obe = std::log2(be[1] / be[2]);
  std::printf("order: Crank-Nicolson %.2f, backward Euler %.2f\n", ocn, obe);
  EXPECT_GT(ocn, 1.8);
  EXPECT_LT(ocn, 2.3);
  EXPECT_GT(obe, 0.8);
  EXPECT_LT(obe, 1.3);
}

}  // namespace
}  // namespace rift
