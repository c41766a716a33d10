// The parallel fluid assembly (systems/fluid/fluid_assembly.hpp: blocks of tets coloured so that a
// colour's blocks share no node) is bitwise deterministic: the momentum matrix and right-hand side, the
// pressure matrix, the pressure right-hand side and the projected gradients come out with the same bits in
// arenas of 1, 2, 4 and 8 threads (this machine grants at most 2; the blocks and colours do not depend on
// it either way), and agree with the sequential loops of kernels/fluid_element.hpp to round-off (a row
// gets its contributions colour by colour instead of in plain tet order). The mesh is large enough for
// several blocks and colours (6,144 tets), its nodes are perturbed and every optional input (SUPG,
// absorption, target, source, body force, Dirichlet nodes) is on; the same holds with the tets shuffled
// (no locality: many colours). Then whole solver steps, both pressure couplings: velocity and pressure
// bitwise equal on 1 and 2 threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "engine/linear/csr_matrix.hpp"
#include "engine/mesh/structured_box.hpp"
#include "kernels/fluid_element.hpp"
#include "systems/fluid/fluid_assembly.hpp"
#include "systems/fluid/fluid_solver.hpp"

namespace rift::fluid {
namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

struct Problem {
  size_t nn = 0, nt = 0;
  std::vector<double> x, volume, grad, h;
  std::vector<int32_t> tets, slot, diag;
  CsrMatrix pattern;
  std::vector<double> u_old, advect, pressure, tau_s, sigma, target, source, body, coef, value, xi;
  std::vector<uint8_t> fixed;
};

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Problem make_problem(bool shuffle = false) {
  StructuredBoxSpec spec;
  spec.cells = {16, 8, 8};
  const TetMesh mesh = structured_box(spec);
  Problem p;
  p.nn = mesh.nodes.size();
  p.nt = mesh.tets.size();
  std::mt19937_64 rng(7);
  for (const auto& n : mesh.nodes)
    for (double c : n) p.x.push_back(c + uniform(rng, -0.01, 0.01));
  std::vector<std::array<int32_t, 4>> tets(mesh.tets.begin(), mesh.tets.end());
  if (shuffle) std::shuffle(tets.begin(), tets.end(), rng);
  for (const auto& t : tets) p.tets.insert(p.tets.end(), t.begin(), t.end());
  p.volume.assign(p.nt, 0.0);
  p.grad.assign(12 * p.nt, 0.0);
  p.h.assign(p.nt, 0.0);
  EXPECT_EQ(kernels::p1_prepare(p.x, p.tets, p.volume, p.grad, p.h), 0u);
  p.pattern = p1_pattern(static_cast<int32_t>(p.nn), p.tets);
  p.slot = p1_tet_slots(p.pattern, p.tets);
  p.diag = diagonal_slots(p.pattern);
  const auto fill = [&](std::vector<double>& v, size_t n, double lo, double hi) {
    v.resize(n);
    for (double& e : v) e = uniform(rng, lo, hi);
  };
  fill(p.u_old, 3 * p.nn, -1, 1);
  fill(p.advect, 3 * p.nn, -1, 1);
  fill(p.pressure, p.nn, -5, 5);
  fill(p.tau_s, p.nt, 0, 1e-2);
  fill(p.sigma, p.nt, 0, 10);
  fill(p.target, 3 * p.nt, -1, 1);
  fill(p.source, 3 * p.nt, -1, 1);
  fill(p.body, 3 * p.nn, -1, 1);
  fill(p.coef, p.nt, 0.5, 2);
  fill(p.value, p.nn, -1, 1);
  fill(p.xi, 3 * p.nn, -1, 1);
  p.fixed.assign(p.nn, 0);
  for (size_t n = 0; n < p.nn; ++n) p.fixed[n] = p.x[3 * n] < 0.02 ? 1 : 0;
  return p;
}

kernels::FluidMomentumArgs momentum_args(const Problem& p, std::vector<double>& val,
                                         std::vector<double>& rhs) {
  kernels::FluidMomentumArgs a;
  a.rho = 1.2;
  a.mu = 0.03;
  a.dt = 0.05;
  a.theta = 0.5;
  a.tet_nodes = p.tets;
  a.volume = p.volume;
  a.grad = p.grad;
  a.slot = p.slot;
  a.u_old = p.u_old;
  a.advect = p.advect;
  a.pressure = p.pressure;
  a.supg_tau = p.tau_s;
  a.sigma = p.sigma;
  a.target = p.target;
  a.source = p.source;
  a.body_force = p.body;
  a.matrix_values = val;
  a.rhs = rhs;
  return a;
}

// All four parallel passes on `threads` threads, into fresh arrays (filled with garbage first: the
// passes write, they do not accumulate).
struct Assembled {
  std::vector<double> matrix, rhs, laplacian, prhs, gradient;
};
Assembled assemble(const Problem& p, int threads) {
  Assembled r;
  r.matrix.assign(p.pattern.nnz(), 7.0);
  r.rhs.assign(3 * p.nn, 7.0);
  r.laplacian.assign(p.pattern.nnz(), 7.0);
  r.prhs.assign(p.nn, 7.0);
  r.gradient.assign(3 * p.nn, 7.0);
  const FluidAssembly asm_(p.tets, p.nn);
  tbb::task_arena arena(threads);
  arena.execute([&] {
    asm_.momentum(momentum_args(p, r.matrix, r.rhs));
    asm_.laplacian_matrix(
        {p.tets, p.volume, p.grad, p.coef, p.slot, p.diag, p.fixed, p.value, r.laplacian, {}});
    asm_.pressure_rhs({p.tets, p.volume, p.grad, p.u_old, p.pressure, p.xi, p.tau_s}, r.prhs);
    asm_.weighted_gradient({p.tets, p.volume, p.grad, p.pressure, p.coef}, r.gradient);
  });
  return r;
}

void check_deterministic_and_close_to_sequential(const Problem& p) {
  const Assembled one = assemble(p, 1);
  for (int threads : {2, 4, 8}) {
    const Assembled many = assemble(p, threads);
    EXPECT_TRUE(same_bits(one.matrix, many.matrix)) << threads << " threads";
    EXPECT_TRUE(same_bits(one.rhs, many.rhs)) << threads;
    EXPECT_TRUE(same_bits(one.laplacian, many.laplacian)) << threads;
    EXPECT_TRUE(same_bits(one.prhs, many.prhs)) << threads;
    EXPECT_TRUE(same_bits(one.gradient, many.gradient)) << threads;
  }
  std::vector<double> matrix(p.pattern.nnz(), 0.0), rhs(3 * p.nn, 0.0), lap(p.pattern.nnz(), 0.0),
      prhs(p.nn, 0.0), gradient(3 * p.nn, 0.0);
  kernels::fluid_assemble_momentum(momentum_args(p, matrix, rhs));
  kernels::scalar_laplacian_assemble(
      {p.tets, p.volume, p.grad, p.coef, p.slot, p.diag, p.fixed, p.value, lap, {}});
  kernels::fluid_pressure_rhs(p.tets, p.volume, p.grad, p.u_old, p.pressure, p.xi, p.tau_s, prhs);
  kernels::p1_weighted_gradient(p.tets, p.volume, p.grad, p.pressure, p.coef, gradient);
  const auto near = [](const std::vector<double>& a, const std::vector<double>& b) {
    double scale = 0.0, err = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      scale = std::max(scale, std::abs(a[i]));
      err = std::max(err, std::abs(a[i] - b[i]));
    }
    return err <= 1e-13 * scale;
  };
  EXPECT_TRUE(near(matrix, one.matrix));
  EXPECT_TRUE(near(rhs, one.rhs));
  EXPECT_TRUE(near(lap, one.laplacian));
  EXPECT_TRUE(near(prhs, one.prhs));
  EXPECT_TRUE(near(gradient, one.gradient));
}

TEST(FluidAssembly, BitwiseIdenticalOn1248ThreadsAndCloseToTheSequentialLoops) {
  const Problem p = make_problem();
  ASSERT_GT(p.nt, 4 * FluidAssembly::kTetGrain);
  const FluidAssembly a(p.tets, p.nn);
  EXPECT_GE(a.colours(), 2u);
  EXPECT_LE(a.colours(), 6u);  // 6 blocks of consecutive tets
  check_deterministic_and_close_to_sequential(p);
}

TEST(FluidAssembly, ShuffledTetsStillDeterministic) {
  const Problem p = make_problem(true);
  check_deterministic_and_close_to_sequential(p);
}

// A closed box with a moving lid (the 3-D cavity), a few steps on 1 and 2 threads.
void run_steps(PressureCoupling coupling, int threads, std::vector<double>& u, std::vector<double>& p) {
  StructuredBoxSpec spec;
  spec.cells = {8, 8, 4};
  FluidSettings st;
  st.rho = 1.0;
  st.mu = 0.01;
  st.dt = 0.1;
  st.coupling = coupling;
  st.picard_max_iterations = 2;
  std::vector<FluidBoundary> bcs{{"ymax",
                                  BoundaryKind::velocity,
                                  [](const Vec3&, double) {
                                    return Vec3{1, 0, 0};
                                  },
                                  {}},
                                 {"xmin", BoundaryKind::no_slip, {}, {}},
                                 {"xmax", BoundaryKind::no_slip, {}, {}},
                                 {"ymin", BoundaryKind::no_slip, {}, {}},
                                 {"zmin", BoundaryKind::no_slip, {}, {}},
                                 {"zmax", BoundaryKind::no_slip, {}, {}}};
  tbb::task_arena arena(threads);
  arena.execute([&] {
    FluidSolver s(structured_box(spec), st, bcs);
    for (int i = 0; i < 3; ++i) s.step();
    u.assign(s.velocity().begin(), s.velocity().end());
    p.assign(s.pressure().begin(), s.pressure().end());
  });
}

TEST(FluidAssembly, SolverStepsBitwiseIdenticalOn1And2Threads) {
  for (const PressureCoupling c : {PressureCoupling::projection, PressureCoupling::schur_gmres}) {
    std::vector<double> u1, p1, u2, p2;
    run_steps(c, 1, u1, p1);
    run_steps(c, 2, u2, p2);
    double umax = 0.0;
    for (double v : u1) umax = std::max(umax, std::abs(v));
    EXPECT_GT(umax, 0.5);  // the lid moves the fluid
    EXPECT_TRUE(same_bits(u1, u2)) << (c == PressureCoupling::projection ? "projection" : "schur");
    EXPECT_TRUE(same_bits(p1, p2)) << (c == PressureCoupling::projection ? "projection" : "schur");
  }
}

}  // namespace
}  // namespace rift::fluid
