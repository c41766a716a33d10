#pragma once
// The fluid step of the concurrent coupling (fluid_solid.coupling: concurrent, docs/coupling.md) as one
// long task beside the solid's sub-steps of a window.
//
// launch() must be called inside the step graph's task arena: the task then shares the run's threads, and
// the fluid's own parallel_for uses whichever of them the solid leaves idle. The task only advances the
// solver (FluidStepSystem::advance): it reads the committed fluid state and writes the solver's spares, the
// pressure preconditioner's coefficients and the pressure subscale, which only the fluid step reads, so
// the run loop may write outputs, metrics and health checks of the last committed step while it runs.
// join() waits for it (helping with its work) and commits its step into the store.
#include <tbb/task_group.h>

#include <cstdint>

#include "systems/fluid/fluid_step_system.hpp"

namespace rift {

class ConcurrentFluidStep {
 public:
  explicit ConcurrentFluidStep(FluidStepSystem& step) : step_(step) {}
  ~ConcurrentFluidStep();  // a last-resort join: the run loop joins before it tears the world down

  // Starts the fluid step from start_time (the window's start). Inside the step graph's arena.
  void launch(double start_time);
  // Waits for the task, rethrows what it threw, and commits its step into the store. Inside the step
  // graph's arena; does nothing when no task runs.
  void join();
  bool running() const { return running_; }

  double task_seconds() const { return task_seconds_; }  // inside the fluid step
  double wait_seconds() const { return wait_seconds_; }  // the run loop waiting in join()
  int64_t steps() const { return steps_; }

 private:
  FluidStepSystem& step_;
  tbb::task_group group_;
  bool running_ = false;
  bool deferred_ = false;  // one thread: the step waits for join()
  double deferred_start_ = 0.0;
  double task_seconds_ = 0.0, wait_seconds_ = 0.0;
  int64_t steps_ = 0;
};

}  // namespace rift
