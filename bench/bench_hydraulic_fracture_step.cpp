// The coupled step of a hydraulic fracture (the jointed solid and the fluid in its cracks) beside the same
// scene dry, in the same run: scenes/validation/radial_toughness.yaml, the quarter penny on a graded
// lattice of 127,000 tets (one scene definition for the CLI, the tests and this benchmark). The issue's
// budget: the fracture flow at most 25 % of the solid step at 1e5 tets. Items are tet-steps.
// Arguments: threads; flow = 0 (the scene without fracture_flow), 1 (zero viscosity, as the scene: one
// pressure per crack), 2 (water, 1 mPa s: a flow solve every step). The first 400 steps (the starter
// crack filling) run before the timing. Counters: the network's triangles and the fracture flow's share
// of the step's system time. Tiny (RIFT_BENCH_TINY): the same scene on 0.25 m cells.
#include <benchmark/benchmark.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_common.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/fracture_flow/fracture_flow_tables.hpp"
#include "systems/simulation.hpp"

namespace {

constexpr int64_t kWarmUpSteps = 400;

// The scene (scenes/<path>) with its overrides, without its fracture_flow when `dry`, after `warm_up` steps.
std::unique_ptr<rift::Simulation> start_scene(const std::string& path,
                                              const std::vector<std::string>& overrides, bool dry,
                                              int threads, int64_t warm_up) {
  rift::Scene scene = rift::load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/" + path, overrides);
  if (dry) scene.fracture_flow.reset();
  rift::RunOptions o;
  o.write_output = false;
  o.progress = false;
  o.threads = threads;
  spdlog::set_level(spdlog::level::warn);
  auto sim = std::make_unique<rift::Simulation>(std::move(scene), o);
  for (int64_t s = 0; s < warm_up; ++s) sim->step_once();
  return sim;
}

std::unique_ptr<rift::Simulation> start(int threads, int flow) {
  std::vector<std::string> overrides;
  if (flow == 2) overrides.push_back("fracture_flow.viscosity=1.0e-3");
  if (rift::bench::tiny())  // coarser cells, and the fracture zone one of their layers either side
    for (const char* o : {"mesh.generate.graded.size=0.25", "solid.fracture.box_min=[-1, -1, -0.2]",
                          "solid.fracture.box_max=[3, 3, 0.2]"})
      overrides.push_back(o);
  return start_scene("validation/radial_toughness.yaml", overrides, flow == 0, threads,
                     rift::bench::tiny() ? 4 : kWarmUpSteps);
}

// The systems' time so far, and the fracture flow's part of it (output and checkpoints left out).
std::pair<double, double> system_seconds(rift::Simulation& sim) {
  double all = 0.0, fracture_flow = 0.0;
  for (const auto& t : sim.graph().timings()) {
    if (t.name == "output" || t.name == "checkpoint") continue;
    all += t.seconds;
    if (t.name == "fracture_flow") fracture_flow += t.seconds;
  }
  return {all, fracture_flow};
}

// Times the steps; counters: tets, threads and, coupled, the network's triangles and the fracture flow's
// share of the systems' time.
void time_steps(benchmark::State& state, rift::Simulation& sim, int threads, bool coupled) {
  const rift::Store& store = sim.world().store;
  const size_t tets = store.table("solid_tet").size();
  const auto before = system_seconds(sim);
  for (auto _ : state) sim.step_once();
  const auto after = system_seconds(sim);
  state.counters["tets"] = static_cast<double>(tets);
  state.counters["threads"] = threads;
  if (coupled) {
    const auto joined = store.table(rift::fracture_flow::joint_table).span<const int64_t>("joined");
    state.counters["network_triangles"] =
        static_cast<double>(std::count_if(joined.begin(), joined.end(), [](int64_t k) { return k >= 0; }));
    state.counters["flow_share"] = (after.second - before.second) / (after.first - before.first);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(tets));
}

void BM_HydraulicFractureStep(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const int flow = static_cast<int>(state.range(1));
  time_steps(state, *start(threads, flow), threads, flow > 0);
}

// The budget at its figure: scenes/bench/network_slab.yaml, 124,416 tets and a crack of 10,368
// triangles over the slab's mid-plane, water (a conjugate-gradient solve every step). Arguments: threads;
// flow = 0 (dry) or 1. Counters as above, and the network's triangles. Tiny: 24 x 24 x 4 cells.
std::unique_ptr<rift::Simulation> start_slab(int threads, int flow) {
  std::vector<std::string> overrides;
  if (rift::bench::tiny()) overrides.push_back("mesh.generate.cells=[24, 24, 4]");
  return start_scene("bench/network_slab.yaml", overrides, flow == 0, threads, rift::bench::tiny() ? 2 : 20);
}

void BM_LargeNetworkStep(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const int flow = static_cast<int>(state.range(1));
  time_steps(state, *start_slab(threads, flow), threads, flow > 0);
}

}  // namespace

BENCHMARK(BM_LargeNetworkStep)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->ArgNames({"threads", "flow"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BM_HydraulicFractureStep)
    ->ArgsProduct({{1, 2}, {0, 1, 2}})
    ->ArgNames({"threads", "flow"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
