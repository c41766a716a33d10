#pragma once
// A run's step written out as a script: the stages one thread would go through, in order. The
// composition root writes it for each configuration of a scene (systems/step_script.cpp); the run loop
// (engine/run_loop.cpp) follows it. A stage is one of three kinds:
//  - graph: systems run in the step graph (engine/schedule/step_graph.hpp), which runs at the same time
//    what their declared access allows and keeps this order for the rest;
//  - beside: work launched before the graph on the first step of each window of `every` steps, running
//    beside the graph's systems over the window's steps, and joined after the graph on its last step
//    (the concurrent fluid step, docs/coupling.md);
//  - after: serial work once the graph is done, on the last step of each window of `every` steps (the
//    concurrent coupling's exchanges, remaking the adaptive fluid mesh).
// A stage with every = N runs once per window of N steps (the fluid window); with every = 1, each step.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/schedule/system.hpp"

namespace rift {

// What a `beside` stage runs. launch() and join() are called inside the step graph's task arena, so a
// task launched there shares the run's threads.
class BackgroundWork {
 public:
  virtual ~BackgroundWork() = default;
  virtual void launch(const StepContext& at) = 0;  // on the first step of a window, before the graph
  // Waits for the work (helping with it) and rethrows what it threw; nothing when none runs. On the last
  // step of a window, and mid-window before anything reads the whole store (a checkpoint, the final state
  // hash) and on the way out.
  virtual void join() = 0;
  // Every column the work reads or writes while it runs: the run refuses to start when a system of the
  // graph touches one of them, since the two run at the same time.
  virtual Access access() const = 0;
};

struct StepStage {
  enum class Kind { graph, beside, after };
  Kind kind = Kind::graph;
  std::string name;  // what the stage does, in the log and `rift graph`
  int64_t every = 1;
  std::vector<System*> systems;                 // graph
  BackgroundWork* work = nullptr;               // beside
  std::function<void(const StepContext&)> run;  // after: the context of the step just taken
};

class StepPlan {
 public:
  // Systems run in the step graph; null entries (a system the scene does not need) are left out, and a
  // stage left empty is dropped.
  StepPlan& graph(std::string name, std::vector<System*> systems, int64_t every = 1);
  StepPlan& beside(std::string name, BackgroundWork& work, int64_t every);
  StepPlan& after(std::string name, int64_t every, std::function<void(const StepContext&)> run);

  const std::vector<StepStage>& stages() const { return stages_; }
  // The graph stages' systems in script order, and the window of each.
  std::vector<System*> graph_systems() const;
  std::vector<int64_t> graph_periods() const;
  std::vector<BackgroundWork*> background() const;
  // One line per stage ("  1. forces on the solid's nodes: surface_loads, tet_forces"), for the log and
  // `rift graph`.
  std::string script() const;

 private:
  StepPlan& add(StepStage stage);  // checks the window
  std::vector<StepStage> stages_;
};

// Whether a stage of window `every` starts (beside: launches) at the step `ctx` describes.
inline bool starts_window(int64_t every, const StepContext& ctx) {
  return ctx.step % every == 0;
}

}  // namespace rift
