// Throughput of the central-difference node update (kernels/central_difference.hpp) over the private
// nodes of the same FDEM meshes as bench_tet_force (4 nodes per tet), at 1 and 2 threads.
//
// Byte model (performance.md 3.1, "Nodal update"): 152 B per node = x read+write 48 + v read+write 48 +
// f read 24 + f zeroed 24 + 1/m 8. Every written line was read first, so there is no extra write-allocate
// traffic. Not in the model: the 3-byte free mask per node of this interface (155 B in all).
// roofline_frac = model bytes/s over the STREAM triad x 4/3 measured at start-up in this process.
#include <cstdint>
#include <vector>

#include "bench/bench_common.hpp"
#include "kernels/central_difference.hpp"

namespace {

constexpr double kModelBytes = 152.0;
constexpr size_t kGrain = 4096;  // nodes; 1024 tets' worth

void BM_NodeUpdate(benchmark::State& state) {
  const size_t target = static_cast<size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const rift::bench::BenchMesh& m = rift::bench::cached_tet_mesh(target, rift::bench::NodeLayout::private_);
  const size_t nodes = m.num_nodes;
  std::vector<double> x = m.x, v = m.v, f(3 * nodes, 1.0), inv_mass(nodes, 1.0 / 3.3e-4);
  std::vector<uint8_t> free_mask(3 * nodes, 1);
  const rift::kernels::CentralDifferenceInput in{1e-7, {0.0, 0.0, -9.81}};
  for (auto _ : state) {
    rift::bench::parallel_ranges(threads, nodes, kGrain, [&](size_t begin, size_t end) {
      rift::kernels::central_difference(in, x, v, f, inv_mass, free_mask, begin, end);
    });
    benchmark::ClobberMemory();
  }
  rift::bench::report_throughput(state, nodes, kModelBytes, threads);
  state.counters["tets_per_second"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(m.num_tets), benchmark::Counter::kIsRate);
  state.counters["nodes"] = static_cast<double>(nodes);
}
BENCHMARK(BM_NodeUpdate)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
