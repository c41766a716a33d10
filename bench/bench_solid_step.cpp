// The whole solid step through the engine (surface loads, tet forces, node integration, scheduled by
// the step graph) on generated meshes, at 1 and 2 threads. Items are tet-steps: what a user's scene
// costs per tet and step, schedule included. (The per-kernel benchmarks carry the byte models.)
// joints = 1: the whole block is a fracture zone (4 private nodes per tet, a 6-node joint on every
// interior face, limestone joint properties; nothing breaks under this load), so the step adds the joint
// forces and the node pass gathers about 3 joint corners per node besides its tet corner.
#include <benchmark/benchmark.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_common.hpp"
#include "engine/scene/load_scene.hpp"
#include "engine/simulation.hpp"

namespace {

// A clamped limestone block under an end traction, sized so the mesh has about `tets` tetrahedra.
std::string block_scene(double tets, bool joints) {
  const double volume = 0.1 * 0.05 * 0.05;
  // The generator gives about 4.4 tets per h^3 of volume at uniform size h (measured: 363,773 tets at
  // h = 1.44 mm in this block).
  const double h = std::cbrt(4.4 * volume / tets);
  const std::string fracture =
      joints ? ",\n      fracture: {tensile_strength: 5.0e6, cohesion: 1.5e7, friction_angle: 35, G_I: 30, "
               "G_II: 300}"
             : "";
  return "scene: {name: bench-solid}\n"
         "time: {end: 1.0, safety: 0.5}\n"
         "mesh:\n  generate: {box: [0.1, 0.05, 0.05], size_min: " +
         std::to_string(h) + ", size_max: " + std::to_string(h) +
         "}\n"
         "solid:\n  materials: [{name: rock, density: 2650, young: 4.0e10, poisson: 0.25, damping: 0.05" +
         fracture +
         "}]\n"
         "  boundaries:\n    - {surface: xmin, type: fixed}\n"
         "    - {surface: xmax, type: traction, direction: [1, 0, 0], value: 1.0e6}\n" +
         (joints ? "  fracture: {regions: [all]}\n" : "");
}

struct Cached {
  double target = 0;
  int threads = 0;
  bool joints = false;
  std::unique_ptr<rift::Simulation> sim;
};

rift::Simulation& simulation(double tets, int threads, bool joints) {
  static Cached cache;
  if (!cache.sim || cache.target != tets || cache.threads != threads || cache.joints != joints) {
    cache.sim.reset();
    auto result = rift::read_scene_text(block_scene(tets, joints), "bench_solid_step", ".");
    if (!result.scene) throw std::runtime_error("bench scene invalid: " + result.errors.front().format());
    rift::RunOptions o;
    o.write_output = false;
    o.progress = false;
    o.threads = threads;
    spdlog::set_level(spdlog::level::warn);
    cache.sim = std::make_unique<rift::Simulation>(std::move(*result.scene), o);
    cache.target = tets;
    cache.threads = threads;
    cache.joints = joints;
  }
  return *cache.sim;
}

std::vector<double> system_seconds(rift::Simulation& sim) {
  std::vector<double> s;
  for (const auto& t : sim.graph().timings()) s.push_back(t.seconds);
  return s;
}

void BM_SolidStep(benchmark::State& state) {
  const double target = rift::bench::tiny() ? 1e3 : static_cast<double>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bool joints = state.range(2) != 0;
  rift::Simulation& sim = simulation(target, threads, joints);
  const size_t tets = sim.world().store.table("solid_tet").size();
  const std::vector<double> before = system_seconds(sim);
  for (auto _ : state) sim.step_once();
  const std::vector<double> after = system_seconds(sim);
  state.counters["tets"] = static_cast<double>(tets);
  if (joints) state.counters["joints"] = static_cast<double>(sim.world().store.table("solid_joint").size());
  // Wall time inside each system per item (ns). At 1 thread the systems run one after another, so these
  // split the step; at 2 threads tet and joint forces may overlap in the graph.
  const double steps = static_cast<double>(state.iterations());
  auto per_item = [&](const char* system, const char* table) {
    const size_t items = sim.world().store.has(table) ? sim.world().store.table(table).size() : 0;
    const auto& timings = sim.graph().timings();
    for (size_t i = 0; i < timings.size(); ++i)
      if (timings[i].name == system && items > 0)
        state.counters[std::string("ns_per_") + (table + 6)] =
            1e9 * (after[i] - before[i]) / (steps * static_cast<double>(items));
  };
  per_item("tet_forces", "solid_tet");
  per_item("joint_forces", "solid_joint");
  per_item("node_integration", "solid_node");
  state.counters["threads"] = threads;
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * tets));
}

}  // namespace

BENCHMARK(BM_SolidStep)
    ->ArgsProduct({{10000, 100000, 1000000}, {1, 2}, {0, 1}})
    ->ArgNames({"tets", "threads", "joints"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
