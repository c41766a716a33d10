// Solid volume fraction on the fluid mesh (kernels/volume_fraction.hpp): the exact intersection kernel at 1
// and 2 threads, and the bipartite broad phase (sequential) timed on its own.
//
// Scene (argument "tets" = fluid tets): the fluid is bench_common's perturbed Kuhn mesh with shared nodes
// (5 mm cells; 1e4 / 1e5 / 1e6 tets, the counter "fluid_tets" gives the exact number). The solid is a
// structured box of half the fluid's side in cells of 5.5 mm (comparable resolution, not a multiple), 6
// tets per cell, turned by 0.5 rad about (1, 2, 3) around the fluid's centre (its half-diagonal, 0.43 of the
// fluid's side, keeps it inside): ~1/11 as many solid tets as fluid tets (counter "solid_tets"). Candidate
// pairs come from coupling_broad_phase with no buffer; a Kuhn tet fills 1/6 of its box, so many candidates
// do not intersect (counter "intersecting").
//
// Byte model (compulsory traffic per call): per pair, the pair 8 B + solid connectivity 16 B + 4 solid
// node positions 96 B = 120 B read; per fluid tet with pairs, connectivity 16 B + positions 96 B read; per
// fluid tet, 2 outputs written 16 B (x2 with write-allocate) = 32 B. bytes/s and roofline_frac use that
// total per pair (counter "model_bytes_per_pair"; the solid nodes are re-read by ~8 tets each and mostly hit
// in cache, so this overstates DRAM traffic). Each pair costs a few hundred to ~2000 flops (4 plane tests
// of 4 + 4 corners, up to 4 clips and a fan), so the kernel is compute-bound: roofline_frac << 1, pairs/s
// is the figure. fluid_tets_per_second counts every fluid tet, with or without pairs.
//
// Broad phase: one call on the same boxes (boxes computed once outside the timing); items = fluid tets.
#include <cmath>
#include <memory>
#include <vector>

#include "bench/bench_common.hpp"
#include "engine/mesh/structured_box.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/volume_fraction.hpp"

namespace {

using rift::kernels::CouplingBroadPhaseArgs;
using rift::kernels::CouplingBroadPhaseWorkspace;
using rift::kernels::CouplingPair;
using rift::kernels::VolumeFractionArgs;
using rift::kernels::VolumeFractionStatus;

constexpr size_t kGrain = 256;
constexpr double kFluidCell = 5e-3, kSolidCell = 5.5e-3;

struct Scene {
  const rift::bench::BenchMesh* fluid = nullptr;
  std::vector<double> solid_x;
  std::vector<int32_t> solid_tets;
  std::vector<double> fluid_lo, fluid_hi, solid_lo, solid_hi;
  std::vector<CouplingPair> pairs, intersecting;  // all candidates; those with a non-zero volume
  size_t fluid_tets = 0, solid_tets_count = 0;
  CouplingBroadPhaseArgs broad_args() const { return {fluid_lo, fluid_hi, solid_lo, solid_hi, 0.0}; }
};

size_t distinct_fluid_tets(const std::vector<CouplingPair>& pairs) {
  size_t n = 0;
  for (size_t i = 0; i < pairs.size(); ++i) n += i == 0 || pairs[i].fluid != pairs[i - 1].fluid;
  return n;
}

void boxes(std::span<const double> x, std::span<const int32_t> tets, std::vector<double>& lo,
           std::vector<double>& hi) {
  const size_t n = tets.size() / 4;
  std::vector<int32_t> ids(n);
  for (size_t i = 0; i < n; ++i) ids[i] = static_cast<int32_t>(i);
  lo.resize(3 * n);
  hi.resize(3 * n);
  rift::kernels::tet_bounding_boxes(x, tets, ids, lo, hi, 0, n);
}

// The solid block, turned by 0.5 rad about (1, 2, 3) (Rodrigues) around the fluid's centre.
void make_solid(double side, Scene& s) {
  const double c = 0.5 * side, half = 0.25 * side;
  const int cells = std::max(1, static_cast<int>(std::lround(2.0 * half / kSolidCell)));
  const rift::TetMesh block = rift::structured_box(
      {{c - half, c - half, c - half}, {c + half, c + half, c + half}, {cells, cells, cells}});
  const double len = std::sqrt(14.0), k[3] = {1.0 / len, 2.0 / len, 3.0 / len};
  const double cs = std::cos(0.5), sn = std::sin(0.5);
  for (const auto& p : block.nodes) {
    const double v[3] = {p[0] - c, p[1] - c, p[2] - c};
    const double kv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    const double kd = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    for (int d = 0; d < 3; ++d) s.solid_x.push_back(c + v[d] * cs + kv[d] * sn + k[d] * kd * (1.0 - cs));
  }
  for (const auto& t : block.tets) s.solid_tets.insert(s.solid_tets.end(), t.begin(), t.end());
  s.solid_tets_count = block.tets.size();
}

// One scene at a time (its fluid mesh is bench_common's single cached mesh).
const Scene& scene(size_t target) {
  static std::unique_ptr<Scene> cached;
  static size_t cached_target = 0;
  if (cached && cached_target == target) return *cached;
  cached.reset();
  cached = std::make_unique<Scene>();
  cached_target = target;
  Scene& s = *cached;
  s.fluid = &rift::bench::cached_tet_mesh(target, rift::bench::NodeLayout::shared);
  s.fluid_tets = s.fluid->num_tets;
  const double side = kFluidCell * std::round(std::cbrt(static_cast<double>(s.fluid_tets) / 6.0));
  make_solid(side, s);
  boxes(s.fluid->x, s.fluid->tet_nodes, s.fluid_lo, s.fluid_hi);
  boxes(s.solid_x, s.solid_tets, s.solid_lo, s.solid_hi);
  CouplingBroadPhaseWorkspace ws;
  rift::kernels::coupling_broad_phase(s.broad_args(), ws);
  s.pairs = ws.pairs;
  // The candidates that do intersect, for the breakdown benchmark (one pair at a time through the kernel).
  std::vector<double> v(1), a(1);
  for (const CouplingPair& p : s.pairs) {
    const CouplingPair one[1] = {{0, p.solid}};
    const VolumeFractionArgs args{
        s.fluid->x, std::span<const int32_t>(s.fluid->tet_nodes).subspan(4 * size_t(p.fluid), 4),
        s.solid_x,  s.solid_tets,
        one,        v,
        a};
    rift::kernels::volume_fraction(args, 0, 1);
    if (v[0] > 0.0) s.intersecting.push_back(p);
  }
  return s;
}

void run(benchmark::State& state, bool intersecting_only) {
  const Scene& s = scene(static_cast<size_t>(state.range(0)));
  const std::vector<CouplingPair>& pairs_in = intersecting_only ? s.intersecting : s.pairs;
  const int threads = static_cast<int>(state.range(1));
  std::vector<double> volume(s.fluid_tets, 0.0), fraction(s.fluid_tets, 0.0);
  const VolumeFractionArgs args{s.fluid->x, s.fluid->tet_nodes, s.solid_x, s.solid_tets, s.pairs, volume,
                                fraction};
  for (auto _ : state) {
    rift::bench::parallel_ranges(threads, s.fluid_tets, kGrain, [&](size_t begin, size_t end) {
      rift::kernels::volume_fraction(args, begin, end);
    });
    benchmark::ClobberMemory();
  }
  const VolumeFractionStatus status = rift::kernels::volume_fraction(args, 0, s.fluid_tets);  // counts, once
  const double pairs = static_cast<double>(pairs_in.size());
  const double bytes = 120.0 * pairs + 112.0 * static_cast<double>(distinct_fluid_tets(pairs_in)) +
                       32.0 * static_cast<double>(s.fluid_tets);
  rift::bench::report_throughput(state, pairs_in.size(), bytes / pairs, threads);
  state.counters["fluid_tets_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(s.fluid_tets),
                         benchmark::Counter::kIsRate);
  state.counters["fluid_tets"] = static_cast<double>(s.fluid_tets);
  state.counters["solid_tets"] = static_cast<double>(s.solid_tets_count);
  state.counters["pairs"] = pairs;
  state.counters["intersecting"] = static_cast<double>(status.intersecting);
  state.counters["cut_fluid_tets"] = static_cast<double>(status.cut);
  state.counters["model_bytes_per_pair"] = bytes / pairs;
}

void BM_VolumeFraction(benchmark::State& state) {
  run(state, false);
}
// Only the candidates that intersect (the broad phase's other ~3/4 removed): the cost of a clipped pair.
void BM_VolumeFractionIntersectingOnly(benchmark::State& state) {
  run(state, true);
}

void BM_VolumeFractionBroadPhase(benchmark::State& state) {
  const Scene& s = scene(static_cast<size_t>(state.range(0)));
  CouplingBroadPhaseWorkspace ws;
  rift::kernels::coupling_broad_phase(s.broad_args(), ws);  // warm: capacities in place
  rift::kernels::CouplingBroadPhaseStats stats;
  for (auto _ : state) {
    stats = rift::kernels::coupling_broad_phase(s.broad_args(), ws);
    benchmark::DoNotOptimize(ws.pairs.data());
  }
  // Boxes read 48 B per fluid and per solid tet, pairs written 8 B (x2 write-allocate), per fluid tet.
  const double bytes =
      48.0 * static_cast<double>(s.fluid_tets + s.solid_tets_count) + 16.0 * static_cast<double>(stats.pairs);
  rift::bench::report_throughput(state, s.fluid_tets, bytes / static_cast<double>(s.fluid_tets), 1);
  state.counters["pairs_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(stats.pairs),
                         benchmark::Counter::kIsRate);
  state.counters["fluid_tets"] = static_cast<double>(s.fluid_tets);
  state.counters["solid_tets"] = static_cast<double>(s.solid_tets_count);
  state.counters["pairs"] = static_cast<double>(stats.pairs);
  state.counters["tests_per_fluid_tet"] =
      static_cast<double>(stats.tested) / static_cast<double>(s.fluid_tets);
  state.counters["grows"] = static_cast<double>(ws.grows);
}

void broad_sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"tets"});
  for (int64_t n :
       rift::bench::tiny() ? std::vector<int64_t>{1000} : std::vector<int64_t>{10000, 100000, 1000000})
    b->Args({n});
}

BENCHMARK(BM_VolumeFraction)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VolumeFractionIntersectingOnly)
    ->Apply(rift::bench::tet_sizes_and_threads)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VolumeFractionBroadPhase)->Apply(broad_sizes)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
