// Contact: broad phase (contact_broad_phase.hpp) against the O(n^2) reference and CGAL 5.5's
// box_self_intersection_d on the same boxes, and the narrow phase (contact_potential.hpp) on overlapping
// tet pairs at 1 and 2 threads.
//
// Boxes (argument "cloud"): 0 = the bounding boxes of bench_common's perturbed Kuhn mesh (5 mm cells,
// ~2e3 / 1e4 / 1e5 / 1e6 tets; the counter "boxes" gives the exact number): a Kuhn tet's box is its whole
// cell, so each box meets ~70 others and the output dominates; 1 = a uniform random cloud of tet-sized
// boxes (random_cloud below, ~2 pairs per box), where the binning itself dominates. Buffer 0.25 mm. All three
// methods report the same pair set (counter "pairs"; the CGAL callback collects the pairs and sorts them, so
// that its output is the same sorted list as ours; "pairs" is compared and the benchmark fails with an error
// if it differs). CGAL reorders its input, so each iteration copies the boxes first (included in its time, ~1
// % of it). Byte model of a broad-phase box (compulsory traffic, bytes/s counter): box 48 B + id 4 B read,
// and 8 B per output pair written (x 2 with write-allocate) = 52 + 16 pairs/box; the scratch (sorted entries
// and boxes) is not counted. The kernel is not bandwidth-bound (roofline_frac ~ 0.01): items/s is the figure.
//
// Narrow phase: pairs of random tets of ~5 mm with private nodes (8 per pair, pair after pair in memory),
// B offset from A by up to 0.3 of the size, so ~90 % overlap (counter "touching"). Byte model per pair:
// pair 8 B + connectivity 32 B + positions 8 x 24 = 192 B read, corner forces 24 x 8 = 192 B written
// (x 2 with write-allocate): 616 B; with friction and damping add velocities 192 B, history 24 B read +
// 24 B written and two dissipations 16 B: 872 B. Compute-bound (32 polygon clips per pair): items/s is the
// figure. A third case runs the pairs the broad phase finds on the 1e5 mesh (touching neighbours sharing
// nodes: mostly zero force, the cost of a candidate that does not overlap).
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "bench/bench_common.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/contact_potential.hpp"

namespace {

using rift::kernels::BroadPhaseArgs;
using rift::kernels::BroadPhaseWorkspace;
using rift::kernels::ContactArgs;
using rift::kernels::ContactPair;

constexpr double kBuffer = 0.25e-3;
constexpr size_t kGrain = 256;

struct BoxSet {
  size_t n = 0;
  std::vector<int32_t> ids;
  std::vector<double> lo, hi;
  std::vector<double> x;  // the mesh, kept for the mesh-pair narrow phase
  std::vector<int32_t> tet_nodes;
  BroadPhaseArgs args() const { return {ids, lo, hi, kBuffer, {}}; }
};

// A uniform random cloud of n tet-sized boxes: edges uniform in [2.5, 5] mm per axis, lower corners
// uniform in a cube holding one box per (5 mm)^3 (a sixth of the mesh's density): ~2 pairs per box.
void random_cloud(size_t n, BoxSet& b) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double side = 5e-3 * std::cbrt(static_cast<double>(n));
  b.n = n;
  b.ids.resize(n);
  b.lo.resize(3 * n);
  b.hi.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    b.ids[i] = static_cast<int32_t>(i);
    for (int k = 0; k < 3; ++k) {
      b.lo[3 * i + k] = side * u(rng);
      b.hi[3 * i + k] = b.lo[3 * i + k] + 2.5e-3 * (1.0 + u(rng));
    }
  }
}

enum Source : int64_t { mesh = 0, cloud = 1 };

const BoxSet& boxes(size_t target, int64_t source = mesh) {
  static std::map<std::pair<size_t, int64_t>, std::unique_ptr<BoxSet>> cache;
  const std::pair<size_t, int64_t> key{target, source};
  auto& slot = cache[key];
  if (!slot) {
    for (auto& [k, b] : cache)
      if (k != key && b && b->n >= 500000) b.reset();  // hold one large set at a time
    if (source == cloud) {
      slot = std::make_unique<BoxSet>();
      random_cloud(target, *slot);
      return *slot;
    }
    const rift::bench::BenchMesh m = rift::bench::make_tet_mesh(target, rift::bench::NodeLayout::shared);
    slot = std::make_unique<BoxSet>();
    BoxSet& b = *slot;
    b.n = m.num_tets;
    b.ids.resize(b.n);
    for (size_t i = 0; i < b.n; ++i) b.ids[i] = static_cast<int32_t>(i);
    b.lo.resize(3 * b.n);
    b.hi.resize(3 * b.n);
    rift::kernels::tet_bounding_boxes(m.x, m.tet_nodes, b.ids, b.lo, b.hi, 0, b.n);
    b.x = m.x;
    b.tet_nodes = m.tet_nodes;
  }
  return *slot;
}

// Arguments {boxes, source}: source 0 = mesh tets, 1 = uniform cloud.
void broad_sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"boxes", "cloud"});
  for (int64_t source : {mesh, cloud}) {
    if (rift::bench::tiny()) {
      b->Args({1000, source});
      continue;
    }
    for (int64_t n : {2000, 10000, 100000, 1000000}) b->Args({n, source});
  }
}
// Ours at 1 and 2 threads (the sweep in chunks on the arena): {boxes, source, threads}.
void broad_sizes_and_threads(benchmark::internal::Benchmark* b) {
  b->ArgNames({"boxes", "cloud", "threads"});
  for (int64_t source : {mesh, cloud}) {
    if (rift::bench::tiny()) {
      b->Args({1000, source, 2});
      continue;
    }
    for (int64_t n : {10000, 100000, 1000000})
      for (int64_t t : {1, 2}) b->Args({n, source, t});
  }
}

// The sweep's chunks on the benchmark's arena of `threads` threads.
int g_threads = 1;
void run_chunks_on_arena(size_t count, rift::kernels::ChunkBody body, void* context) {
  rift::bench::parallel_ranges(g_threads, count, 1, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) body(context, k);
  });
}
void brute_sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"boxes", "cloud"});
  for (int64_t source : {mesh, cloud}) {
    if (rift::bench::tiny()) {
      b->Args({1000, source});
      continue;
    }
    for (int64_t n : {2000, 10000}) b->Args({n, source});
  }
}

void report_broad(benchmark::State& state, const BoxSet& b, size_t pairs, int threads = 1) {
  const double per_box = 52.0 + 16.0 * static_cast<double>(pairs) / static_cast<double>(b.n);
  rift::bench::report_throughput(state, b.n, per_box, threads);
  state.counters["boxes"] = static_cast<double>(b.n);
  state.counters["pairs"] = static_cast<double>(pairs);
}

// The reference count for a box set, from our kernel (checked against the brute force in the unit tests).
size_t reference_pairs(const BoxSet& b) {
  BroadPhaseWorkspace ws;
  return rift::kernels::contact_broad_phase(b.args(), ws).pairs;
}

void BM_BroadPhase(benchmark::State& state) {
  const BoxSet& b = boxes(static_cast<size_t>(state.range(0)), state.range(1));
  g_threads = static_cast<int>(state.range(2));
  auto args = b.args();
  args.run_chunks = &run_chunks_on_arena;
  BroadPhaseWorkspace ws;
  rift::kernels::contact_broad_phase(args, ws);  // warm: capacities in place
  rift::kernels::BroadPhaseStats st;
  for (auto _ : state) {
    st = rift::kernels::contact_broad_phase(args, ws);
    benchmark::DoNotOptimize(ws.pairs.data());
  }
  if (st.pairs != reference_pairs(b)) state.SkipWithError("threaded pair count differs");
  report_broad(state, b, st.pairs, g_threads);
  state.counters["tests_per_box"] = static_cast<double>(st.tested) / static_cast<double>(b.n);
  state.counters["grows"] = static_cast<double>(ws.grows);
}

void BM_BroadPhaseBruteForce(benchmark::State& state) {
  const BoxSet& b = boxes(static_cast<size_t>(state.range(0)), state.range(1));
  size_t pairs = 0;
  for (auto _ : state) {
    const auto p = rift::kernels::contact_broad_phase_brute_force(b.args());
    pairs = p.size();
    benchmark::DoNotOptimize(p.data());
  }
  if (pairs != reference_pairs(b)) state.SkipWithError("brute force pair count differs");
  report_broad(state, b, pairs);
}

void BM_BroadPhaseCgal(benchmark::State& state) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int32_t>;
  const BoxSet& b = boxes(static_cast<size_t>(state.range(0)), state.range(1));
  const double h = 0.5 * kBuffer;
  std::vector<Box> master;
  master.reserve(b.n);
  for (size_t i = 0; i < b.n; ++i) {
    double l[3], u[3];
    for (int k = 0; k < 3; ++k) {
      l[k] = b.lo[3 * i + k] - h;
      u[k] = b.hi[3 * i + k] + h;
    }
    master.emplace_back(l, u, b.ids[i]);
  }
  std::vector<Box> work;
  std::vector<ContactPair> pairs;
  for (auto _ : state) {
    work = master;
    pairs.clear();
    CGAL::box_self_intersection_d(work.begin(), work.end(), [&](const Box& p, const Box& q) {
      const int32_t a = p.info(), c = q.info();
      pairs.push_back({std::min(a, c), std::max(a, c)});
    });
    std::sort(pairs.begin(), pairs.end());
    benchmark::DoNotOptimize(pairs.data());
  }
  if (pairs.size() != reference_pairs(b)) state.SkipWithError("CGAL pair count differs");
  report_broad(state, b, pairs.size());
}

BENCHMARK(BM_BroadPhase)->Apply(broad_sizes_and_threads)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BroadPhaseBruteForce)->Apply(brute_sizes)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BroadPhaseCgal)->Apply(broad_sizes)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------------------------------------------------
// Narrow phase

struct PairSet {
  std::vector<double> x, v;
  std::vector<int32_t> tet_nodes;
  std::vector<ContactPair> pairs;
};

PairSet overlapping_pairs(size_t count) {
  PairSet s;
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const double size = 5e-3;
  for (size_t p = 0; p < count; ++p) {
    const double origin[3] = {0.02 * static_cast<double>(p % 100), 0.02 * static_cast<double>(p / 100 % 100),
                              0.02 * static_cast<double>(p / 10000)};
    const double offset[3] = {0.3 * size * u(rng), 0.3 * size * u(rng), 0.3 * size * u(rng)};
    for (int t = 0; t < 2; ++t) {
      // A regular-ish tet of edge ~size, corners moved by up to 0.15 size.
      const double corner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.866, 0}, {0.5, 0.289, 0.816}};
      for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 3; ++k) {
          s.x.push_back(origin[k] + (t == 1 ? offset[k] : 0.0) + size * (corner[c][k] + 0.3 * u(rng)));
          s.v.push_back(0.1 * u(rng));
        }
      for (int c = 0; c < 4; ++c) s.tet_nodes.push_back(static_cast<int32_t>(8 * p + 4 * t + c));
    }
    s.pairs.push_back({static_cast<int32_t>(2 * p), static_cast<int32_t>(2 * p + 1)});
  }
  return s;
}

void narrow(benchmark::State& state, const PairSet& s, bool friction) {
  const int threads = static_cast<int>(state.range(1));
  const size_t P = s.pairs.size();
  std::vector<double> force(24 * P), history(3 * P, 0.0), fdiss(P), ddiss(P);
  rift::kernels::ContactLaw law;
  law.penalty = 4e11;
  if (friction) {
    law.friction = 0.6;
    law.tangential_stiffness = 1e6;
    law.normal_damping = 10.0;
  }
  ContactArgs args{
      s.x,  friction ? std::span<const double>(s.v) : std::span<const double>(), s.tet_nodes, s.pairs, law,
      1e-7, friction ? std::span<double>(history) : std::span<double>(),         force};
  if (friction) {
    args.friction_dissipation = fdiss;
    args.damping_dissipation = ddiss;
  }
  rift::kernels::ContactStatus total;
  for (auto _ : state) {
    rift::bench::parallel_ranges(threads, P, kGrain, [&](size_t begin, size_t end) {
      rift::kernels::contact_forces(args, begin, end);
    });
    benchmark::ClobberMemory();
  }
  total = rift::kernels::contact_forces(args, 0, P);
  rift::bench::report_throughput(state, P, friction ? 872.0 : 616.0, threads);
  state.counters["pairs"] = static_cast<double>(P);
  state.counters["touching"] = static_cast<double>(total.touching) / static_cast<double>(P);
}

const PairSet& cached_pairs(size_t count) {
  static std::map<size_t, std::unique_ptr<PairSet>> cache;
  auto& slot = cache[count];
  if (!slot) slot = std::make_unique<PairSet>(overlapping_pairs(count));
  return *slot;
}

void narrow_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"pairs", "threads"});
  const std::vector<int64_t> sizes =
      rift::bench::tiny() ? std::vector<int64_t>{500} : std::vector<int64_t>{10000, 100000};
  for (int64_t n : sizes)
    for (int64_t t : {1, 2}) b->Args({n, t});
}

void BM_NarrowPhase(benchmark::State& state) {
  narrow(state, cached_pairs(static_cast<size_t>(state.range(0))), false);
}
void BM_NarrowPhaseFriction(benchmark::State& state) {
  narrow(state, cached_pairs(static_cast<size_t>(state.range(0))), true);
}
// The pairs of the broad phase on a mesh (range(0) tets): neighbours whose boxes overlap.
void BM_NarrowPhaseMeshPairs(benchmark::State& state) {
  const BoxSet& b = boxes(static_cast<size_t>(state.range(0)));
  BroadPhaseWorkspace ws;
  rift::kernels::contact_broad_phase(b.args(), ws);
  PairSet s;
  s.x = b.x;
  s.tet_nodes = b.tet_nodes;
  s.pairs = ws.pairs;
  if (!rift::bench::tiny() && s.pairs.size() > 1000000) s.pairs.resize(1000000);
  narrow(state, s, false);
}

BENCHMARK(BM_NarrowPhase)->Apply(narrow_args)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NarrowPhaseFriction)->Apply(narrow_args)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NarrowPhaseMeshPairs)
    ->ArgNames({"tets", "threads"})
    ->Args({rift::bench::tiny() ? 1000 : 10000, 1})
    ->Args({rift::bench::tiny() ? 1000 : 10000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
