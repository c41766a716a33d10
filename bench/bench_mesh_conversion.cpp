// Mesh conversion (engine/mesh/mesh_conversion.hpp) on Kuhn lattice boxes of ~1e4, 1e5 and 1e6 tets, all
// in the fracture zone (4 private nodes per tet, a joint on every interior face):
//   BM_ConversionUpdate  the incremental update for k newly broken joints (k = 1, 64, 4096), joints drawn
//                        at random (clustered = 0, the worst case for locality) or in joint order
//                        (clustered = 1: neighbouring joints, as along a crack front); items = joints. The
//                        claim under test: the cost per joint does not grow with the mesh. The state is
//                        rebuilt (untimed) once 20 % of the joints are broken, so every size is measured in
//                        the same regime.
//   BM_ConversionBuild   the whole build from scratch, for comparison: items = tets.
//   BM_ConversionKinematics  vertex positions and velocities as mass-weighted means of the copies, at 1
//                        and 2 threads; items = node copies. Byte model per copy: x, v, mass read 56 B, its
//                        vertex id and CSR entry 8 B; per vertex: x, v, mass accumulated (56 B written with
//                        write-allocate, 112 B) and the division pass (48 B read, 48 B written): 208 B.
#include <algorithm>
#include <memory>
#include <numeric>
#include <random>

#include "bench/bench_common.hpp"
#include "engine/mesh/discontinuous_mesh.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/mesh_conversion.hpp"

namespace {

using rift::MeshConversion;

struct Fixture {
  size_t cells = 0;
  rift::TetMesh mesh;
  rift::DiscontinuousMesh dm;
  std::vector<double> x, v, mass;
  std::vector<int32_t> order;  // joints in random order

  rift::SolidTopology topology() const {
    rift::SolidTopology t;
    t.input_vertex_count = mesh.nodes.size();
    t.node_vertex = dm.node_vertex;
    t.tet_nodes = {&dm.tets[0][0], 4 * dm.tets.size()};
    t.joint_nodes = {&dm.joints[0][0], 6 * dm.joints.size()};
    t.joint_tets = {&dm.joint_tets[0][0], 2 * dm.joint_tets.size()};
    return t;
  }
};

// n^3 cubes x 6 tets with n = round(cbrt(tets / 6)): 1e4 -> 12^3 x 6 = 10,368; 1e5 -> 26^3 x 6 = 105,456;
// 1e6 -> 55^3 x 6 = 998,250. One fixture is kept at a time.
const Fixture& fixture(size_t target_tets) {
  static std::unique_ptr<Fixture> held;
  const size_t n = std::max<size_t>(1, size_t(std::lround(std::cbrt(double(target_tets) / 6.0))));
  if (held && held->cells == n) return *held;
  held.reset();
  auto f = std::make_unique<Fixture>();
  f->cells = n;
  const int c = static_cast<int>(n);
  f->mesh = rift::generate_lattice_box({c, c, c}, {0.005 * c, 0.005 * c, 0.005 * c});
  f->dm = rift::make_discontinuous(f->mesh, [](size_t) { return true; });
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& p : f->dm.nodes)
    for (int k = 0; k < 3; ++k) f->x.push_back(p[k] + 1e-6 * u(rng));
  f->v.resize(f->x.size());
  for (double& w : f->v) w = u(rng);
  f->mass.assign(f->dm.nodes.size(), 1e-3);
  f->order.resize(f->dm.joints.size());
  std::iota(f->order.begin(), f->order.end(), 0);
  std::shuffle(f->order.begin(), f->order.end(), rng);
  held = std::move(f);
  return *held;
}

void sizes(benchmark::internal::Benchmark* b, bool with_threads, bool with_k) {
  const std::vector<int64_t> tets =
      rift::bench::tiny() ? std::vector<int64_t>{1000} : std::vector<int64_t>{10000, 100000, 1000000};
  for (int64_t t : tets) {
    if (with_k) {
      for (int64_t k : {1, 64, 4096})
        for (int64_t clustered : {0, 1})
          if (k <= t / 2) b->Args({t, k, clustered});  // a tiny mesh has fewer joints than the largest batch
    } else if (with_threads) {
      for (int64_t th : {1, 2}) b->Args({t, th});
    } else {
      b->Args({t});
    }
  }
}

void BM_ConversionUpdate(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<size_t>(state.range(0)));
  const size_t k = static_cast<size_t>(state.range(1));
  const bool clustered = state.range(2) != 0;
  const size_t limit = std::max(k, f.order.size() / 5);
  auto conv = std::make_unique<MeshConversion>(f.topology());
  size_t next = 0, folded = 0;
  for (auto _ : state) {
    if (next + k > limit) {
      state.PauseTiming();
      conv = std::make_unique<MeshConversion>(f.topology());
      next = 0;
      state.ResumeTiming();
    }
    for (size_t i = 0; i < k; ++i)
      conv->break_joint(clustered ? static_cast<int32_t>(next + i) : f.order[next + i], 0.0);
    next += k;
    folded += k;
  }
  state.SetItemsProcessed(static_cast<int64_t>(folded));
  state.counters["tets"] = static_cast<double>(f.dm.tets.size());
  // Rate of (joints x 1e-9), inverted: seconds per 1e-9 joints = nanoseconds per joint.
  state.counters["ns_per_joint"] = benchmark::Counter(
      1e-9 * static_cast<double>(folded), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ConversionUpdate)
    ->ArgNames({"tets", "k", "clustered"})
    ->Apply([](auto* b) { sizes(b, false, true); }) -> Unit(benchmark::kMicrosecond);

void BM_ConversionBuild(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<size_t>(state.range(0)));
  for (auto _ : state) {
    MeshConversion conv(f.topology());
    benchmark::DoNotOptimize(conv.vertex_count());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * f.dm.tets.size()));
  state.counters["tets"] = static_cast<double>(f.dm.tets.size());
}
BENCHMARK(BM_ConversionBuild)->ArgNames({"tets"})->Apply([](auto* b) {
                                                   sizes(b, false, false);
                                                 }) -> Unit(benchmark::kMillisecond);

void BM_ConversionKinematics(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<size_t>(state.range(0)));
  const int threads = static_cast<int>(state.range(1));
  MeshConversion conv(f.topology());
  for (size_t i = 0; i < f.order.size() / 20; ++i) conv.break_joint(f.order[i], 0.0);  // 5 % broken
  for (auto _ : state) rift::bench::arena(threads).execute([&] { conv.update_kinematics(f.x, f.v, f.mass); });
  const size_t copies = f.dm.nodes.size();
  const double bytes_per_copy = 64.0 + 208.0 * double(conv.vertex_count()) / double(copies);
  rift::bench::report_throughput(state, copies, bytes_per_copy, threads);
  state.counters["tets"] = static_cast<double>(f.dm.tets.size());
}
BENCHMARK(BM_ConversionKinematics)
    ->ArgNames({"tets", "threads"})
    ->Apply([](auto* b) { sizes(b, true, false); }) -> Unit(benchmark::kMicrosecond) -> UseRealTime();

}  // namespace
