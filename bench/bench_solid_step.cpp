// The whole solid step through the engine (surface loads, tet forces, node integration, scheduled by
// the step graph) on generated meshes, at 1 and 2 threads. Items are tet-steps: what a user's scene
// costs per tet and step, schedule included.
// joints = 1: the whole block is a fracture zone (4 private nodes per tet, a 6-node joint on every
// interior face, limestone joint properties; nothing breaks under this load), so the step adds the joint
// forces and the node pass gathers about 3 joint corners per node besides its tet corner.
// fused = 1 (the default, solid.fused_tet_pass): the node pass computes the tets with nodes of their own
// and gathers their joints per tet; 0: a separate tet pass and the per-node gather (jointed 1e5 only).
// observe_all = 1: every step computes the derived fields (stress, strain energy, the joints' opening,
// slip, damage and stored energy, the nodes' total force), as step_once does by default; 0: only every
// 16th, as in a run (StepContext::observed: outputs, metrics and energy checks read them).
//
// Byte model: the compulsory traffic of the engine's interfaces per step (write-allocate counted), from
// the per-kernel models (bench_tet_force, bench_joint_force, bench_node_update) with the engine's columns:
//   per tet    508 B: positions 96, velocities 96, Dm^-1 72, V0 8, material 4, connectivity 16, corner
//              forces 96 x 2, viscous power 8 x 2 + 8 read for the sum; observed +112 (stress 48 x 2,
//              energy 8 x 2);
//   per joint  293 B (3 points): bench_joint_force's 269 (forces only) + initial offset 24; observed +64;
//   per node   135 B: x and v read and written 96, mass and 1/m 16, free mask 3, held condition 12, slot
//              range 8; observed +48 (total force written, x 2);
//   per slot   28 B: its index 4 and the corner-force row it reads 24 (4 per tet, 6 per joint, 3 per loaded
//              face; a joint's row is read by both of its corners);
//   per loaded face 228 B (3 positions 72, connectivity 12, corner forces 72 x 2).
// Fused (every tet of the jointed block): per tet 145 B (the 508 less the corner forces and the positions
// and velocities, which the node pass reads from cache right after the tet kernel; plus the face table,
// 21 B); per node 127 B (no slot range); per joint slot 24 B (the row, no index); no tet slots.
// bytes_per_second and roofline_frac (over the same-process STREAM triad x 4/3) use it.
#include <benchmark/benchmark.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_common.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"

namespace {

// A clamped limestone block under an end traction, sized so the mesh has about `tets` tetrahedra.
std::string block_scene(double tets, bool joints, bool fused) {
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
         "solid:\n  fused_tet_pass: " +
         std::string(fused ? "true" : "false") +
         "\n  materials: [{name: rock, density: 2650, young: 4.0e10, poisson: 0.25, damping: 0.05" +
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
  bool fused = true;
  std::unique_ptr<rift::Simulation> sim;
};

rift::Simulation& simulation(double tets, int threads, bool joints, bool fused) {
  static Cached cache;
  if (!cache.sim || cache.target != tets || cache.threads != threads || cache.joints != joints ||
      cache.fused != fused) {
    cache.sim.reset();
    auto result = rift::read_scene_text(block_scene(tets, joints, fused), "bench_solid_step", ".");
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
    cache.fused = fused;
  }
  return *cache.sim;
}

std::vector<double> system_seconds(rift::Simulation& sim) {
  std::vector<double> s;
  for (const auto& t : sim.graph().timings()) s.push_back(t.seconds);
  return s;
}

// Bytes per tet-step of the model above, for the mesh of `sim`, observed on 1 step in `every`.
double model_bytes_per_tet(rift::Simulation& sim, int64_t every, bool fused) {
  const rift::Store& store = sim.world().store;
  auto rows = [&](const char* table) {
    return store.has(table) ? static_cast<double>(store.table(table).size()) : 0.0;
  };
  const double tets = rows("solid_tet"), joints = rows("solid_joint"), nodes = rows("solid_node");
  const double faces = rows("solid_load_face");
  const double slots = 4 * tets + 6 * joints + 3 * faces;
  const double base =
      fused && joints > 0
          ? 145 * tets + 293 * joints + 127 * nodes + 24 * 6 * joints + 28 * 3 * faces + 228 * faces
          : 508 * tets + 293 * joints + 135 * nodes + 28 * slots + 228 * faces;
  const double observed = 112 * tets + 64 * joints + 48 * nodes;
  return (base + observed / static_cast<double>(every)) / tets;
}

void BM_SolidStep(benchmark::State& state) {
  const double target = rift::bench::tiny() ? 1e3 : static_cast<double>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bool joints = state.range(2) != 0;
  const bool observe_all = state.range(3) != 0;
  const bool fused = state.range(4) != 0;
  rift::Simulation& sim = simulation(target, threads, joints, fused);
  sim.observe_every_step(observe_all);
  const size_t tets = sim.world().store.table("solid_tet").size();
  const std::vector<double> before = system_seconds(sim);
  for (auto _ : state) sim.step_once();
  const std::vector<double> after = system_seconds(sim);
  state.counters["tets"] = static_cast<double>(tets);
  if (joints) state.counters["joints"] = static_cast<double>(sim.world().store.table("solid_joint").size());
  // Wall time inside each system per item (ns). At 1 thread the systems run one after another, so these
  // split the step; at 2 threads tet and joint forces may overlap in the graph. Fused, the tets' time is
  // in the node pass's.
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
  rift::bench::report_throughput(
      state, tets, model_bytes_per_tet(sim, observe_all ? 1 : rift::kObservedEvery, fused), threads);
}

}  // namespace

BENCHMARK(BM_SolidStep)
    ->ArgsProduct({{10000, 100000, 1000000}, {1, 2}, {0, 1}, {0, 1}, {1}})
    ->ArgsProduct({{100000}, {1, 2}, {1}, {0}, {0}})
    ->ArgNames({"tets", "threads", "joints", "observe_all", "fused"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
