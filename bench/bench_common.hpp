#pragma once
// Shared pieces of the Google Benchmark executables (bench/CMakeLists.txt links this file into each one):
// main() (measures the STREAM triad once at start-up, then runs the selected benchmarks), the triad itself
// as a benchmark and as the roofline reference, thread arenas, and a perturbed structured tet mesh.
//
// RIFT_BENCH_TINY=1 shrinks every size (~10^3 tets, small triad arrays) so CI can run each benchmark once
// to keep it compiling and running; the figures of a tiny run mean nothing.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/tet_forces.hpp"

namespace rift::bench {

bool tiny();  // RIFT_BENCH_TINY=1 in the environment

// A reusable arena with exactly `threads` threads (1 or 2 on the project machine); created on first use.
tbb::task_arena& arena(int threads);

// body(begin, end) over [0, n) inside arena(threads), TBB's default (auto) partitioner, chunks >= grain.
template <class Body>
void parallel_ranges(int threads, size_t n, size_t grain, const Body& body) {
  arena(threads).execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                      [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
  });
}

// STREAM triad a = b + s c, best of 5 sweeps over 3 arrays of 64 MiB (x8 the L3), counted the STREAM way
// (24 B per element: two reads, one write; the write-allocate read is not counted). Measured once per thread
// count in main() before the benchmarks; later calls return the stored figure.
double stream_triad_bytes_per_second(int threads);
// What a streaming kernel can really move: the triad's DRAM traffic including write-allocate, x 4/3
// (performance.md 2). The denominator of every roofline_frac counter.
inline double roofline_bytes_per_second(int threads) {
  return stream_triad_bytes_per_second(threads) * 4.0 / 3.0;
}

// Adds the byte-model counters to a kernel benchmark that did `units` units of work per iteration:
// bytes_per_second (SetBytesProcessed with model_bytes per unit), items_per_second, and roofline_frac =
// achieved model bytes/s over roofline_bytes_per_second(threads).
void report_throughput(benchmark::State& state, size_t units, double model_bytes, int threads);

// Benchmark arguments {tets, threads}: tets in {1e4, 1e5, 1e6} (1e3 when tiny), threads in {1, 2}.
void tet_sizes_and_threads(benchmark::internal::Benchmark* b);

enum class NodeLayout {
  shared,   // continuous mesh: (n+1)^3 grid nodes shared by the tets around them
  private_  // FDEM: every tet owns its 4 nodes, stored as nodes 4t..4t+3 (joints tie them in the engine)
};

// n^3 hexes x 6 Kuhn tets, n = round(cbrt(target_tets / 6)) (1e6 -> 55^3 x 6 = 998,250 tets), cell size
// 5 mm, grid nodes moved by up to +-2 % of the cell, then displaced by ~1e-3 of the cell (strains ~1e-3)
// with random velocities. 4 materials (rock-like Lamé constants, eta ~ 0.1 critical), random per tet.
// dm_inv / volume0 come from tet_prepare on x0.
struct BenchMesh {
  size_t num_tets = 0, num_nodes = 0;
  std::vector<double> x0, x, v;
  std::vector<int32_t> tet_nodes, material;
  std::vector<kernels::TetMaterial> materials;
  std::vector<double> dm_inv, volume0;
};
BenchMesh make_tet_mesh(size_t target_tets, NodeLayout layout, uint64_t seed = 1);
// The last mesh asked for, kept so benchmarks over the same size do not rebuild it (one held at a time).
const BenchMesh& cached_tet_mesh(size_t target_tets, NodeLayout layout);

}  // namespace rift::bench
