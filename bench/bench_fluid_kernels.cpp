// Per-kernel throughput of the fluid step (issue 7) on 3-D structured boxes of n^3 cells x 6 Kuhn tets,
// n = 12, 26, 55 (10,368 / 105,456 / 998,250 tets; 8^3 cells when RIFT_BENCH_TINY=1), at 1 and 2
// threads, each also as a fraction of the memory roofline (STREAM triad x 4/3 measured in this process,
// bench_common.hpp):
//   BM_FluidMomentumAssembly      the momentum (velocity-block) matrix and right-hand side, exactly as the
//                                 solver runs it (systems/fluid/fluid_assembly.hpp: coloured blocks of
//                                 tets, each scattered in order into the CSR values); items = tets
//   BM_FluidMomentumAssemblySerial the plain sequential loop (kernels::fluid_assemble_momentum after zeroing
//                                 the outputs), 1 thread: the reference the colouring must not slow down
//   BM_FluidPressureMatrixAssembly the pressure matrix sum_t (c + tau_p)_t K^t with Dirichlet rows, coloured
//                                 as the momentum; items = tets
//   BM_PressureAmgSetup           BoomerAMG set-up on that matrix; items = unknowns (nodes)
//   BM_PressurePcgSolve           AMG-PCG solve to 1e-8 from x = 0; items = unknowns per solve, the PCG
//                                 iterations as a counter (unknown_iterations/s is the rate per iteration)
//   BM_CsrMatVec                  y = A x on the same pattern, rows in parallel blocks: the bandwidth-bound
//                                 reference; items = nonzeros
// hypre is serial (Debian's libHYPRE has no OpenMP), so the AMG benchmarks run at 1 thread only.
//
// Byte models (compulsory DRAM traffic of what the code does, double precision, write-allocate counted as
// a read; node data counted once per node, i.e. perfect reuse of the node gathers). Per tet t, node n,
// CSR nonzero z (on these meshes nodes ~ t/6, nonzeros ~ 15 n ~ 2.5 t):
//   momentum: reads nodes 16 + volume 8 + gradients 96 + tau_s 8 + sigma 8 + target 24 + source 24 +
//     CSR slots 64 = 248 B/t and u^n, w, p 56 B/n; zeroes then scatters into the matrix 16 + 16 B/z and
//     the rhs 48 + 48 B/n: 248 B/t + 32 B/z + 152 B/n  (~353 B/t here). The same for the sequential loop
//     and the coloured one (the colouring adds no traffic).
//   pressure matrix: reads nodes 16 + volume 8 + gradients 96 + coef 8 + slots 64 = 192 B/t and fixed
//     1 B/n, zeroes then scatters 32 B/z, the unit diagonals read fixed and the diagonal slots 5 B/n:
//     192 B/t + 32 B/z + 6 B/n  (~273 B/t).
//   mat-vec: values 8 + columns 4 B/z, row pointers 4 B/row, y 16 B/row (x2), x 8 B/row: 12 B/z + 28 B/row
//     (~13.9 B/z).
//   AMG set-up and PCG: not modelled as bytes (hypre's hierarchy is its own); items/s only.
#include <algorithm>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "bench/bench_common.hpp"
#include "engine/linear/csr_matrix.hpp"
#include "engine/linear/hypre_pcg.hpp"
#include "engine/mesh/structured_box.hpp"
#include "engine/schedule/parallel.hpp"
#include "kernels/fluid_element.hpp"
#include "systems/fluid/fluid_assembly.hpp"

namespace {

using rift::fluid::FluidAssembly;

// One size's mesh, geometry, pattern, assembly maps and fields, built once and kept for all benchmarks.
struct FluidBench {
  size_t nt = 0, nn = 0;
  std::vector<double> x, volume, grad, h;
  std::vector<int32_t> tets, slot, diag;
  rift::CsrMatrix momentum, pressure;
  std::unique_ptr<FluidAssembly> assembly;
  std::vector<double> u_old, advect, p, tau_s, sigma, target, source, rhs, pcoef, value, mv_x, mv_y;
  std::vector<uint8_t> fixed;
  double t() const { return static_cast<double>(nt); }
  double n() const { return static_cast<double>(nn); }
  double z() const { return static_cast<double>(momentum.nnz()); }
};

int cells_for(int64_t tets) {
  if (rift::bench::tiny()) return 8;
  return tets <= 10000 ? 12 : tets <= 100000 ? 26 : 55;
}

FluidBench make_bench(int cells) {
  rift::StructuredBoxSpec spec;
  spec.cells = {cells, cells, cells};
  const rift::TetMesh mesh = rift::structured_box(spec);
  FluidBench b;
  b.nt = mesh.tets.size();
  b.nn = mesh.nodes.size();
  for (const auto& q : mesh.nodes) b.x.insert(b.x.end(), q.begin(), q.end());
  for (const auto& q : mesh.tets) b.tets.insert(b.tets.end(), q.begin(), q.end());
  b.volume.assign(b.nt, 0.0);
  b.grad.assign(12 * b.nt, 0.0);
  b.h.assign(b.nt, 0.0);
  rift::kernels::p1_prepare(b.x, b.tets, b.volume, b.grad, b.h);
  b.momentum = rift::p1_pattern(static_cast<int32_t>(b.nn), b.tets);
  b.pressure = b.momentum;
  b.slot = rift::p1_tet_slots(b.momentum, b.tets);
  b.diag = rift::diagonal_slots(b.momentum);
  b.assembly = std::make_unique<FluidAssembly>(b.tets, b.nn);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto random = [&](std::vector<double>& v, size_t count, double scale) {
    v.resize(count);
    for (double& e : v) e = scale * unit(rng);
  };
  random(b.u_old, 3 * b.nn, 1.0);
  random(b.advect, 3 * b.nn, 1.0);
  random(b.p, b.nn, 1.0);
  b.tau_s.assign(b.nt, 1e-3);
  b.sigma.assign(b.nt, 0.0);  // the solver passes its (zero) coupling hooks every step
  b.target.assign(3 * b.nt, 0.0);
  b.source.assign(3 * b.nt, 0.0);
  b.rhs.assign(3 * b.nn, 0.0);
  b.pcoef.assign(b.nt, 1.0);
  b.value.assign(b.nn, 0.0);
  b.fixed.assign(b.nn, 0);
  for (size_t i = 0; i < b.nn; ++i)
    for (int d = 0; d < 3; ++d) b.fixed[i] |= (b.x[3 * i + d] == 0.0 || b.x[3 * i + d] == 1.0) ? 1 : 0;
  random(b.mv_x, b.nn, 1.0);
  b.mv_y.assign(b.nn, 0.0);
  return b;
}

FluidBench& bench_for(int64_t tets) {
  static std::map<int, std::unique_ptr<FluidBench>> cache;
  const int cells = cells_for(tets);
  auto& slot = cache[cells];
  if (!slot) slot = std::make_unique<FluidBench>(make_bench(cells));
  return *slot;
}

rift::kernels::FluidMomentumArgs momentum_args(FluidBench& b) {
  rift::kernels::FluidMomentumArgs a;
  a.rho = 1.0;
  a.mu = 0.01;
  a.dt = 0.1;
  a.theta = 1.0;
  a.tet_nodes = b.tets;
  a.volume = b.volume;
  a.grad = b.grad;
  a.slot = b.slot;
  a.u_old = b.u_old;
  a.advect = b.advect;
  a.pressure = b.p;
  a.supg_tau = b.tau_s;
  a.sigma = b.sigma;
  a.target = b.target;
  a.source = b.source;
  a.matrix_values = b.momentum.val;
  a.rhs = b.rhs;
  return a;
}

rift::kernels::ScalarLaplacianArgs pressure_args(FluidBench& b) {
  return {b.tets, b.volume, b.grad, b.pcoef, b.slot, b.diag, b.fixed, b.value, b.pressure.val, {}};
}

void counters(benchmark::State& state, const FluidBench& b, size_t items, double bytes_total, int threads) {
  rift::bench::report_throughput(state, items, bytes_total / static_cast<double>(items), threads);
  state.counters["tets"] = b.t();
  state.counters["unknowns"] = b.n();
  state.counters["nonzeros"] = b.z();
  state.counters["bytes_per_item"] = bytes_total / static_cast<double>(items);
  state.counters["colours"] = static_cast<double>(b.assembly->colours());
}

void BM_FluidMomentumAssembly(benchmark::State& state) {
  FluidBench& b = bench_for(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const auto a = momentum_args(b);
  for (auto _ : state) {
    rift::bench::arena(threads).execute([&] { b.assembly->momentum(a); });
    benchmark::ClobberMemory();
  }
  counters(state, b, b.nt, 248.0 * b.t() + 32.0 * b.z() + 152.0 * b.n(), threads);
}

void BM_FluidMomentumAssemblySerial(benchmark::State& state) {
  FluidBench& b = bench_for(state.range(0));
  const auto a = momentum_args(b);
  for (auto _ : state) {
    std::fill(b.momentum.val.begin(), b.momentum.val.end(), 0.0);
    std::fill(b.rhs.begin(), b.rhs.end(), 0.0);
    rift::kernels::fluid_assemble_momentum(a);
    benchmark::ClobberMemory();
  }
  counters(state, b, b.nt, 248.0 * b.t() + 32.0 * b.z() + 152.0 * b.n(), 1);
}

void BM_FluidPressureMatrixAssembly(benchmark::State& state) {
  FluidBench& b = bench_for(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const auto a = pressure_args(b);
  for (auto _ : state) {
    rift::bench::arena(threads).execute([&] { b.assembly->laplacian_matrix(a); });
    benchmark::ClobberMemory();
  }
  counters(state, b, b.nt, 192.0 * b.t() + 32.0 * b.z() + 6.0 * b.n(), threads);
}

// The pressure matrix of BM_FluidPressureMatrixAssembly, assembled once, and a right-hand side of ones on
// the free nodes.
void assemble_pressure(FluidBench& b, std::vector<double>& rhs) {
  b.assembly->laplacian_matrix(pressure_args(b));
  rhs.assign(b.nn, 1.0);
  for (size_t i = 0; i < b.nn; ++i)
    if (b.fixed[i]) rhs[i] = 0.0;
}

void BM_PressureAmgSetup(benchmark::State& state) {
  FluidBench& b = bench_for(state.range(0));
  std::vector<double> rhs;
  assemble_pressure(b, rhs);
  rift::HypreAmgPcg amg;
  for (auto _ : state) amg.set_matrix(b.pressure);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * b.nn));
  state.counters["unknowns"] = b.n();
  state.counters["nonzeros"] = b.z();
}

void BM_PressurePcgSolve(benchmark::State& state) {
  FluidBench& b = bench_for(state.range(0));
  std::vector<double> rhs, u(b.nn, 0.0);
  assemble_pressure(b, rhs);
  rift::HypreAmgPcg amg;
  amg.set_matrix(b.pressure);
  rift::AmgPcgResult res;
  for (auto _ : state) {
    state.PauseTiming();
    std::fill(u.begin(), u.end(), 0.0);
    state.ResumeTiming();
    res = amg.solve(rhs, u);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * b.nn));
  state.counters["unknowns"] = b.n();
  state.counters["pcg_iterations"] = res.iterations;
  state.counters["unknown_iterations_per_second"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * b.n() * res.iterations, benchmark::Counter::kIsRate);
}

void BM_CsrMatVec(benchmark::State& state) {
  FluidBench& b = bench_for(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const rift::CsrMatrix& a = b.momentum;
  for (auto _ : state) {
    rift::bench::arena(threads).execute([&] {
      rift::parallel_for(b.nn, 4096,
                         [&](size_t begin, size_t end) { a.multiply_rows(b.mv_x, b.mv_y, begin, end); });
    });
    benchmark::ClobberMemory();
  }
  counters(state, b, a.nnz(), 12.0 * b.z() + 28.0 * b.n(), threads);
}

void one_thread(benchmark::internal::Benchmark* bm) {
  bm->ArgNames({"tets"});
  for (int64_t tets :
       rift::bench::tiny() ? std::vector<int64_t>{1000} : std::vector<int64_t>{10000, 100000, 1000000})
    bm->Args({tets});
}

BENCHMARK(BM_FluidMomentumAssembly)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FluidMomentumAssemblySerial)->Apply(one_thread)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FluidPressureMatrixAssembly)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PressureAmgSetup)->Apply(one_thread)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PressurePcgSolve)->Apply(one_thread)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CsrMatVec)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
