#pragma once
// The runtime of a run: the world a builder makes from a scene, its step graph, and the loop that advances
// it with outputs, checkpoints, guards and a progress line. The engine knows no physics: which models a
// scene needs is the composition root's (systems/world_builder.hpp), which the CLI, the tests and the
// benchmarks reach through systems/simulation.hpp.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/run_summary.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/step_graph.hpp"
#include "engine/world.hpp"

namespace rift {

struct RunOptions {
  std::filesystem::path out_dir = "rift-out";
  int threads = 1;
  bool restart_latest = false;
  bool progress = true;
  bool write_output = true;                // fields, time series, summary (off for pure benchmarks)
  std::optional<int64_t> stop_after_step;  // stop (with a checkpoint) once this step is done: tests, studies
  // A folder that already holds a run is refused (continue it with restart_latest); overwrite deletes that
  // run's files (Rift's own names only) first.
  bool overwrite = false;
  // Run every step's systems one after another and stop at the first that changes a column it did not
  // declare among its writes, or a table's rows it did not declare among its resizes
  // (engine/schedule/access_check.hpp).
  // For tests: slow.
  bool check_access = false;
};

struct RunResult {
  int64_t steps = 0;
  double time = 0.0;
  bool completed = false;   // reached the end time
  std::string stop_reason;  // "", "signal", "stop_after_step"
  uint64_t state_hash = 0;
  double wall_seconds = 0.0;
};

class RunLoop {
 public:
  // build: makes the world (mesh, store, models) from the scene; it may reject the scene with rift::Error.
  RunLoop(Scene scene, RunOptions options, const WorldBuilder& build);
  ~RunLoop();

  RunResult run();
  void step_once();  // one step without outputs (benchmarks, tests)
  // Whether step_once computes the derived fields on every step (true, the default: a caller may read
  // them after any step) or only on the steps a run reads them after (StepContext::observed).
  void observe_every_step(bool every) { observe_every_step_ = every; }

  const Scene& scene() const { return scene_; }
  World& world() { return *world_; }
  StepGraph& graph() { return *graph_; }
  double dt() const { return dt_; }
  int64_t step() const { return step_; }
  int64_t total_steps() const { return total_steps_; }
  double time() const { return static_cast<double>(step_) * dt_; }

  // Set by SIGINT/SIGTERM handlers: the loop writes a checkpoint and stops at the next step boundary.
  static std::atomic<bool>& interrupt_flag();

 private:
  void check_step_count(double steps, double dt, const std::string& source) const;
  void choose_dt();
  void restart_from_latest();
  void refuse_or_clear_earlier_run();
  void write_output();
  void record_metrics();
  void write_time_series() const;
  void write_checkpoint();
  void write_summary(const RunResult& result) const;
  void log_timing_table() const;
  void check_background_access();
  void start_windows(const StepContext& ctx);  // the plan's stages before the graph
  void end_windows(const StepContext& ctx);    // and after it
  template <class F>
  void in_stage_arena(F&& fn) {
    if (has_background_)
      graph_->in_arena(std::forward<F>(fn));
    else
      fn();
  }
  void remove_killed_writers_files();
  // A run under mpirun with more than one rank (engine/run_split.cpp): each model takes its rank's share;
  // rank 0 alone writes, after the models gather their rows to it.
  bool split() const { return job_size_ > 1; }
  void split_between_ranks();
  void gather_to_root();
  std::optional<std::string> agree_on_stop(const std::optional<std::string>& mine) const;
  unsigned agree_with_rank_zero(unsigned flags) const;
  uint64_t run_state_hash();  // rank 0's, from the gathered store, on every rank
  template <class F>
  void on_every_rank(F&& step);
  void join_background();
  void join_background_quietly() noexcept;

  Scene scene_;
  RunOptions options_;
  std::unique_ptr<World> world_;
  std::unique_ptr<StepGraph> graph_;
  double dt_ = 0.0;
  int64_t step_ = 0;
  int64_t total_steps_ = 0;
  int64_t outputs_written_ = 0;
  bool observe_every_step_ = true;
  bool observe_next_ = false;  // run(): outputs or metrics follow the next step
  std::unique_ptr<class XdmfSeries> series_;
  std::unique_ptr<class CheckpointSet> checkpoints_;
  std::vector<std::string> metric_names_;
  std::vector<std::vector<double>> metric_rows_;
  std::string progress_quantities_;  // the progress line's physics (key_quantities in simulation.cpp)
  double output_seconds_ = 0.0, checkpoint_seconds_ = 0.0;
  bool has_background_ = false;  // a stage of the step plan runs beside the graph
  int job_rank_ = 0, job_size_ = 1;
  bool writes_ = true;  // this process writes the run's files: options_.write_output, on rank 0 of a job
  nlohmann::json partition_summary_;
};

}  // namespace rift
