// What a sum with the same bits in any order costs (kernels/reproducible_sum.hpp) against a plain sum of
// the same terms, one thread, terms in L2 (1e4 doubles) and in memory (1e7): items are terms added.
// Byte model: 8 B a term read. The reproducible sum's 6 flops a term (two grids, two adds, two
// subtractions) form two dependent chains; the plain sum is one add a term, one chain.
#include <random>
#include <vector>

#include "bench/bench_common.hpp"
#include "kernels/reproducible_sum.hpp"

namespace {

std::vector<double> terms(size_t n) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = u(rng);
  return x;
}

void BM_PlainSum(benchmark::State& state) {
  const std::vector<double> x = terms(size_t(state.range(0)));
  for (auto _ : state) {
    double s = 0.0;
    for (double v : x) s += v;
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetBytesProcessed(state.iterations() * state.range(0) * 8);
}

void BM_ReproducibleSum(benchmark::State& state) {
  const std::vector<double> x = terms(size_t(state.range(0)));
  const rift::kernels::ReproducibleGrid g = rift::kernels::reproducible_grid(1.0, int64_t(x.size()));
  for (auto _ : state) {
    rift::kernels::ReproducibleSum s;
    for (double v : x) s.add(v, g);
    benchmark::DoNotOptimize(s.first);
    benchmark::DoNotOptimize(s.second);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetBytesProcessed(state.iterations() * state.range(0) * 8);
}

void sizes(benchmark::internal::Benchmark* b) {
  if (rift::bench::tiny()) {
    b->Arg(1000);
    return;
  }
  b->Arg(10000)->Arg(10000000);
}

BENCHMARK(BM_PlainSum)->Apply(sizes);
BENCHMARK(BM_ReproducibleSum)->Apply(sizes);

}  // namespace
