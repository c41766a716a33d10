#include "bench/bench_common.hpp"

#include <tbb/partitioner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace rift::bench {

bool tiny() {
  static const bool value = [] {
    const char* env = std::getenv("RIFT_BENCH_TINY");
    return env != nullptr && std::strcmp(env, "1") == 0;
  }();
  return value;
}

tbb::task_arena& arena(int threads) {
  static tbb::task_arena arenas[2] = {tbb::task_arena(1), tbb::task_arena(2)};
  return arenas[std::clamp(threads, 1, 2) - 1];
}

// ---------------------------------------------------------------------------------------------------------
// STREAM triad

namespace {

struct FreeDeleter {
  void operator()(double* p) const { std::free(p); }
};
using DoubleArray = std::unique_ptr<double[], FreeDeleter>;

struct TriadArrays {
  size_t n;
  DoubleArray a, b, c;
};

// Explicit 4-wide so the figure does not depend on the optimisation level's vectoriser decisions.
void triad(double* a, const double* b, const double* c, double s, size_t begin, size_t end) {
  size_t i = begin;
#ifdef __AVX2__
  const __m256d sv = _mm256_set1_pd(s);
  for (; i + 4 <= end; i += 4)
    _mm256_storeu_pd(a + i, _mm256_add_pd(_mm256_loadu_pd(b + i), _mm256_mul_pd(sv, _mm256_loadu_pd(c + i))));
#endif
  for (; i < end; ++i) a[i] = b[i] + s * c[i];
}

// One sweep, the range cut statically into one piece per thread (STREAM's OpenMP static schedule).
void triad_sweep(TriadArrays& t, int threads, double s) {
  arena(threads).execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, t.n, 4096),
        [&](const tbb::blocked_range<size_t>& r) {
          triad(t.a.get(), t.b.get(), t.c.get(), s, r.begin(), r.end());
        },
        tbb::static_partitioner());
  });
}

TriadArrays& triad_arrays() {
  static TriadArrays t = [] {
    TriadArrays fresh;
    fresh.n = tiny() ? (size_t{1} << 14) : (size_t{64} << 20) / sizeof(double);  // 64 MiB per array
    auto make = [&] {
      return DoubleArray(static_cast<double*>(std::aligned_alloc(64, fresh.n * sizeof(double))));
    };
    fresh.a = make();
    fresh.b = make();
    fresh.c = make();
    // First touch by the threads that will stream them (one NUMA node here, but it costs nothing).
    arena(2).execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<size_t>(0, fresh.n),
          [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
              fresh.a[i] = 0.0;
              fresh.b[i] = 1.0;
              fresh.c[i] = 2.0;
            }
          },
          tbb::static_partitioner());
    });
    return fresh;
  }();
  return t;
}

double measure_triad(int threads) {
  TriadArrays& t = triad_arrays();
  triad_sweep(t, threads, 3.0);  // warm-up
  double best = 1e300;
  for (int rep = 0; rep < 5; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    triad_sweep(t, threads, 3.0);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return 24.0 * static_cast<double>(t.n) / best;
}

void BM_StreamTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  TriadArrays& t = triad_arrays();
  for (auto _ : state) {
    triad_sweep(t, threads, 3.0);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * 24 * t.n));
}
BENCHMARK(BM_StreamTriad)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

double stream_triad_bytes_per_second(int threads) {
  static double measured[2] = {0.0, 0.0};
  double& value = measured[std::clamp(threads, 1, 2) - 1];
  if (value == 0.0) value = measure_triad(threads);
  return value;
}

void report_throughput(benchmark::State& state, size_t units, double model_bytes, int threads) {
  const double work = static_cast<double>(state.iterations()) * static_cast<double>(units);
  state.SetItemsProcessed(static_cast<int64_t>(work));
  state.SetBytesProcessed(static_cast<int64_t>(work * model_bytes));
  state.counters["roofline_frac"] = benchmark::Counter(
      work * model_bytes / roofline_bytes_per_second(threads), benchmark::Counter::kIsRate);
}

void tet_sizes_and_threads(benchmark::internal::Benchmark* b) {
  b->ArgNames({"tets", "threads"});
  const std::vector<int64_t> sizes =
      tiny() ? std::vector<int64_t>{1000} : std::vector<int64_t>{10000, 100000, 1000000};
  for (int64_t tets : sizes)
    for (int64_t threads : {1, 2}) b->Args({tets, threads});
}

// ---------------------------------------------------------------------------------------------------------
// Structured tet mesh

namespace {

// The 6 Kuhn tets of a cube follow the monotone paths from corner (0,0,0) to (1,1,1), one per permutation
// of the axes; odd permutations are negatively oriented and get two corners swapped.
constexpr int kAxisOrder[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
constexpr bool kOddOrder[6] = {false, true, true, false, false, true};

void add_grid(size_t n, double h, std::mt19937_64& rng, BenchMesh& m) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const size_t side = n + 1;
  m.x0.resize(3 * side * side * side);
  for (size_t k = 0; k < side; ++k)
    for (size_t j = 0; j < side; ++j)
      for (size_t i = 0; i < side; ++i) {
        double* p = &m.x0[3 * (i + side * (j + side * k))];
        p[0] = h * (static_cast<double>(i) + 0.02 * unit(rng));
        p[1] = h * (static_cast<double>(j) + 0.02 * unit(rng));
        p[2] = h * (static_cast<double>(k) + 0.02 * unit(rng));
      }
}

void add_kuhn_tets(size_t n, BenchMesh& m) {
  const size_t side = n + 1;
  m.tet_nodes.reserve(4 * 6 * n * n * n);
  for (size_t k = 0; k < n; ++k)
    for (size_t j = 0; j < n; ++j)
      for (size_t i = 0; i < n; ++i)
        for (int p = 0; p < 6; ++p) {
          size_t c[3] = {i, j, k};
          int32_t t[4];
          t[0] = static_cast<int32_t>(c[0] + side * (c[1] + side * c[2]));
          for (int s = 0; s < 3; ++s) {
            ++c[kAxisOrder[p][s]];
            t[s + 1] = static_cast<int32_t>(c[0] + side * (c[1] + side * c[2]));
          }
          if (kOddOrder[p]) std::swap(t[2], t[3]);
          m.tet_nodes.insert(m.tet_nodes.end(), t, t + 4);
        }
}

// FDEM: copy each tet's corners into nodes 4t..4t+3.
void privatise_nodes(BenchMesh& m) {
  std::vector<double> shared = std::move(m.x0);
  m.x0.resize(12 * m.num_tets);
  for (size_t t = 0; t < m.num_tets; ++t)
    for (int a = 0; a < 4; ++a) {
      const size_t from = static_cast<size_t>(m.tet_nodes[4 * t + a]);
      std::copy_n(&shared[3 * from], 3, &m.x0[3 * (4 * t + a)]);
      m.tet_nodes[4 * t + a] = static_cast<int32_t>(4 * t + a);
    }
}

}  // namespace

BenchMesh make_tet_mesh(size_t target_tets, NodeLayout layout, uint64_t seed) {
  const double h = 5e-3;
  const size_t n = std::max<size_t>(1, static_cast<size_t>(std::lround(std::cbrt(target_tets / 6.0))));
  std::mt19937_64 rng(seed);
  BenchMesh m;
  add_grid(n, h, rng, m);
  add_kuhn_tets(n, m);
  m.num_tets = m.tet_nodes.size() / 4;
  if (layout == NodeLayout::private_) privatise_nodes(m);
  m.num_nodes = m.x0.size() / 3;

  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  m.x.resize(m.x0.size());
  m.v.resize(m.x0.size());
  for (size_t i = 0; i < m.x0.size(); ++i) {
    m.x[i] = m.x0[i] + 1e-3 * h * unit(rng);
    m.v[i] = 1e-2 * unit(rng);
  }
  // Limestone and sandstone of femdem.md 1e and two softer variants; eta ~ 0.1 of 2 h sqrt(E rho).
  m.materials = {{16e9, 16e9, 1e4}, {8.7e9, 7.7e9, 7e3}, {4e9, 4e9, 5e3}, {12e9, 9e9, 8e3}};
  m.material.resize(m.num_tets);
  for (auto& id : m.material) id = static_cast<int32_t>(rng() % m.materials.size());
  m.dm_inv.resize(9 * m.num_tets);
  m.volume0.resize(m.num_tets);
  if (kernels::tet_prepare(m.x0, m.tet_nodes, m.dm_inv, m.volume0, 0, m.num_tets) != 0)
    std::fprintf(stderr, "make_tet_mesh: degenerate tets in the generated mesh\n");
  return m;
}

const BenchMesh& cached_tet_mesh(size_t target_tets, NodeLayout layout) {
  static std::unique_ptr<BenchMesh> mesh;
  static size_t cached_target = 0;
  static NodeLayout cached_layout = NodeLayout::shared;
  if (!mesh || cached_target != target_tets || cached_layout != layout) {
    mesh.reset();  // free the old one before building the next
    mesh = std::make_unique<BenchMesh>(make_tet_mesh(target_tets, layout));
    cached_target = target_tets;
    cached_layout = layout;
  }
  return *mesh;
}

}  // namespace rift::bench

// Every bench executable links this file and gets this main: the triad reference first, then the benchmarks.
int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (int threads : {1, 2}) {
    const double bw = rift::bench::stream_triad_bytes_per_second(threads);
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", bw / 1e9);
    benchmark::AddCustomContext("stream_triad_GBps_" + std::to_string(threads) + "T", text);
  }
  benchmark::AddCustomContext("tet_forces_avx2", rift::kernels::tet_forces_vectorised() ? "yes" : "no");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
