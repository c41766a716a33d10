#pragma once
// The step as a tbb::flow::graph, derived from the systems' declared column access.
//
// Systems are listed in the order the step would run them one after another (the "script" order).
// System j depends on an earlier system i when j reads a column i writes (read after write), writes a
// column i reads (write after read) or writes a column i also writes (write after write), or when one
// resizes a table whose columns the other uses; a system that changes topology is ordered against every
// other system. Everything else may run concurrently.
// Redundant edges (implied through another path) are dropped. The graph is built once per run and
// triggered once per step; each node records its wall time.
#include <tbb/flow_graph.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/schedule/system.hpp"

namespace rift {

// One execution interval of a system, for tests and traces (recorded only when tracing is on).
struct SystemInterval {
  int system = 0;
  double begin = 0.0, end = 0.0;  // seconds since the graph was built
};

class StepGraph {
 public:
  // periods[i]: system i runs on the steps that end each window of that many steps (runs_at) and is
  // skipped on the others; empty: every system runs on every step.
  StepGraph(std::vector<System*> systems, int threads, std::vector<int64_t> periods = {});
  ~StepGraph();

  void run_step(const StepContext& ctx);  // one trigger, returns when every system has run
  // Runs fn inside the graph's task arena (so nested parallel_for uses the configured threads).
  template <class F>
  void in_arena(F&& fn) {
    arena_.execute(std::forward<F>(fn));
  }

  int threads() const { return threads_; }
  const std::vector<std::vector<int>>& successors() const { return successors_; }
  const std::vector<SystemTiming>& timings() const { return timings_; }
  std::string dot() const;  // Graphviz: one box per system, edges labelled with the column that orders them

  void set_tracing(bool on) { tracing_ = on; }
  // Checking mode (engine/schedule/access_check.hpp): each step runs the systems one after another in
  // script order and stops with rift::Error, naming system and column, when one changed a column it did
  // not declare among its writes or a table's rows it did not declare among its resizes. For tests; slow.
  void check_access_against(const Store* store) { checked_store_ = store; }
  const std::vector<SystemInterval>& intervals() const { return intervals_; }

 private:
  void derive_edges();
  void build_flow_graph();
  void run_checked(const StepContext& ctx);

  std::vector<System*> systems_;
  std::vector<Access> access_;
  std::vector<int64_t> periods_;                    // the window of each (step plan)
  std::vector<std::vector<int>> successors_;        // after transitive reduction
  std::vector<std::vector<std::string>> edge_why_;  // column that forced each edge (parallel to successors_)
  std::vector<SystemTiming> timings_;
  int threads_;
  tbb::task_arena arena_;
  std::unique_ptr<tbb::flow::graph> graph_;
  std::unique_ptr<tbb::flow::broadcast_node<tbb::flow::continue_msg>> start_;
  std::vector<std::unique_ptr<tbb::flow::continue_node<tbb::flow::continue_msg>>> nodes_;
  const StepContext* current_ = nullptr;
  const Store* checked_store_ = nullptr;
  bool tracing_ = false;
  std::vector<SystemInterval> intervals_;
  std::chrono::steady_clock::time_point epoch_;
};

}  // namespace rift
