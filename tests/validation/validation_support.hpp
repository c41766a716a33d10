#pragma once
// Shared by the validation tests: load a scene of scenes/validation/ and step it through the same
// Simulation the CLI uses (outputs off), watching the solid after every step.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"
#include "systems/solid_model.hpp"

namespace rift::validation {

inline Scene validation_scene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/" + name, overrides);
}

inline SolidModel& solid_of(Simulation& sim) {
  for (auto& m : sim.world().models)
    if (auto* s = dynamic_cast<SolidModel*>(m.get())) return *s;
  throw std::runtime_error("the scene has no solid");
}

// The solid's time-series row (what timeseries.csv would hold for this step), by name.
class Metrics {
 public:
  explicit Metrics(SolidModel& solid) : solid_(solid) {}
  void update(double time) {
    row_.clear();
    solid_.metrics(time, row_);
  }
  double operator[](const std::string& name) const {
    for (const auto& [n, v] : row_)
      if (n == name) return v;
    ADD_FAILURE() << "no metric " << name;
    return 0.0;
  }

 private:
  SolidModel& solid_;
  std::vector<std::pair<std::string, double>> row_;
};

// Runs the scene to its end time; `watch(sim)` after every step (and once before the first).
inline RunResult run_watching(const Scene& scene, int threads,
                              const std::function<void(Simulation&)>& watch) {
  RunOptions o;
  o.threads = threads;
  o.progress = false;
  o.write_output = false;
  Simulation sim(scene, o);
  watch(sim);
  while (sim.step() < sim.total_steps()) {
    sim.step_once();
    watch(sim);
  }
  RunResult r;
  r.steps = sim.step();
  r.time = sim.time();
  r.completed = true;
  return r;
}

}  // namespace rift::validation
