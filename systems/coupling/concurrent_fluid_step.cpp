#include "systems/coupling/concurrent_fluid_step.hpp"

#include <tbb/task_arena.h>

#include <chrono>

namespace rift {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

ConcurrentFluidStep::~ConcurrentFluidStep() {
  if (!running_) return;
  try {
    group_.wait();
  } catch (...) {  // the run is being torn down; its error, if any, was reported already
  }
}

void ConcurrentFluidStep::launch(double start_time) {
  running_ = true;
  // With --threads 1 the step runs in join(): an enqueued task would make TBB lend the arena a worker
  // (its mandatory concurrency for enqueued work), a second thread the run was not given.
  if (tbb::this_task_arena::max_concurrency() == 1) {
    deferred_ = true;
    deferred_start_ = start_time;
    return;
  }
  // Enqueued (FIFO), not spawned into this thread's deque: a worker picks it up while this thread goes on
  // with the solid's step. The body is isolated so that the thread running it, when it waits inside the
  // fluid's parallel_for, helps only the fluid and never takes a node of the solid's graph (which would
  // then wait for the whole fluid solve).
  tbb::this_task_arena::enqueue(group_.defer([this, start_time] {
    tbb::this_task_arena::isolate([&] {
      const auto t0 = std::chrono::steady_clock::now();
      step_.advance(start_time);
      task_seconds_ += seconds_since(t0);
    });
  }));
}

void ConcurrentFluidStep::join() {
  if (!running_) return;
  const auto t0 = std::chrono::steady_clock::now();
  running_ = false;  // also when the step threw: its exception ends the run, there is nothing to wait for
  try {
    if (deferred_) {
      deferred_ = false;
      step_.advance(deferred_start_);
      task_seconds_ += seconds_since(t0);
    }
    group_.wait();
  } catch (...) {
    wait_seconds_ += seconds_since(t0);
    throw;
  }
  wait_seconds_ += seconds_since(t0);
  ++steps_;
  step_.commit();
}

}  // namespace rift
