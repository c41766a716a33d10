// Throughput of the tet internal-force kernel, AVX2 path and scalar reference, on FDEM meshes (private
// nodes) of 1e4, 1e5 and 1e6 tets at 1 and 2 threads.
//
// Byte model (performance.md 3.1, "Tet, FDEM (private nodes)"): 468 B per tet =
//   positions 4x3x8 = 96 + velocities 96 + Dm^-1 72 + V0 8 + material id 4 + corner forces 12x8 read+write
//   192.
// The forces are written, not accumulated, here, but a fresh write costs the same read (write-allocate) +
// write, so 192 B still holds. The model leaves out what this interface also moves: connectivity 16 B and,
// with all outputs on, stress 48 + energy 8 written (x2 with write-allocate) = 596 B per tet.
// Counters: roofline_frac (468 B model, as in performance.md) and roofline_frac_io (the interface's own
// compulsory traffic: 596 B with stress and energy, 484 B forces only, 612 B with the viscous power written
// too; the initial stress is per material and stays in cache), both over the STREAM triad x 4/3 measured at
// start-up in this process.
#include <vector>

#include "bench/bench_common.hpp"
#include "kernels/tet_forces.hpp"

namespace {

using rift::bench::NodeLayout;
using rift::kernels::TetForceArgs;
using rift::kernels::TetForceStatus;

constexpr double kModelBytes = 468.0;
constexpr double kIoBytesAll = 596.0, kIoBytesForcesOnly = 484.0, kIoBytesExtras = 612.0;
constexpr size_t kGrain = 1024;

// What a call asks for: forces only, + stress and energy, + viscous power and an initial stress.
enum class Outputs { forces, all, extras };

template <TetForceStatus (*Kernel)(const TetForceArgs&, size_t, size_t)>
void run(benchmark::State& state, Outputs outputs) {
  const size_t target = static_cast<size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const rift::bench::BenchMesh& m = rift::bench::cached_tet_mesh(target, NodeLayout::private_);
  std::vector<double> force(12 * m.num_tets, 0.0), stress, energy, power, initial_stress;
  if (outputs != Outputs::forces) {
    stress.assign(6 * m.num_tets, 0.0);
    energy.assign(m.num_tets, 0.0);
  }
  if (outputs == Outputs::extras) {
    power.assign(m.num_tets, 0.0);
    for (size_t k = 0; k < m.materials.size(); ++k)  // in-situ stress of a few tens of MPa, with shear
      initial_stress.insert(initial_stress.end(), {-20e6, -12e6, -30e6, 4e6, -3e6, 5e6});
  }
  const TetForceArgs args{m.x,         m.v,   m.tet_nodes, m.dm_inv, m.volume0, m.material,
                          m.materials, force, stress,      energy,   power,     initial_stress};
  for (auto _ : state) {
    rift::bench::parallel_ranges(threads, m.num_tets, kGrain,
                                 [&](size_t begin, size_t end) { Kernel(args, begin, end); });
    benchmark::ClobberMemory();
  }
  rift::bench::report_throughput(state, m.num_tets, kModelBytes, threads);
  const double io = outputs == Outputs::forces ? kIoBytesForcesOnly
                    : outputs == Outputs::all  ? kIoBytesAll
                                               : kIoBytesExtras;
  state.counters["roofline_frac_io"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(m.num_tets) * io /
                             rift::bench::roofline_bytes_per_second(threads),
                         benchmark::Counter::kIsRate);
  state.counters["tets"] = static_cast<double>(m.num_tets);
}

void BM_TetForces(benchmark::State& state) {
  run<rift::kernels::tet_forces>(state, Outputs::all);
}
void BM_TetForcesScalar(benchmark::State& state) {
  run<rift::kernels::tet_forces_scalar>(state, Outputs::all);
}
// Stress and energy skipped (empty spans), as a solver step that writes no output would call it.
void BM_TetForcesOnly(benchmark::State& state) {
  run<rift::kernels::tet_forces>(state, Outputs::forces);
}
// All outputs plus the viscous power and an initial stress (the optional extensions all on).
void BM_TetForcesExtras(benchmark::State& state) {
  run<rift::kernels::tet_forces>(state, Outputs::extras);
}

BENCHMARK(BM_TetForces)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetForcesScalar)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetForcesOnly)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetForcesExtras)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
