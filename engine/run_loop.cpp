#include "engine/run_loop.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <string_view>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/state_hash.hpp"
#include "engine/distributed/job_agreement.hpp"
#include "engine/distributed/mpi_runtime.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/output_dir.hpp"
#include "engine/io/time_series_csv.hpp"
#include "engine/io/xdmf_series.hpp"
#include "engine/progress.hpp"
#include "engine/scene/scene_diff.hpp"
#include "rift/build_info.hpp"

namespace rift {

namespace {
using clock_type = std::chrono::steady_clock;
double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}
}  // namespace

// In a split run, a step that fails on some ranks fails on all of them, with the lowest rank's message,
// before the next step that needs them all.
template <class F>
void RunLoop::on_every_rank(F&& step) {
  std::optional<std::string> problem;
  try {
    step();
  } catch (const Error& e) {
    if (!split()) throw;
    problem = e.what();
  }
  if (const auto agreed = agree_on_stop(problem)) throw JobError(*agreed);
}

std::atomic<bool>& RunLoop::interrupt_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

RunLoop::RunLoop(Scene scene, RunOptions options, const WorldBuilder& build)
    : scene_(std::move(scene)), options_(std::move(options)) {
  if (launched_rank().size > 1) {
    const MpiRank job = mpi_runtime_init();
    job_rank_ = job.rank;
    job_size_ = job.size;
  }
  writes_ = options_.write_output && job_rank_ == 0;
  // Everything that can reject the input happens before the output folder is touched.
  if (writes_) buffer_log_messages();
  spdlog::info("scene '{}' ({}), hash {}", scene_.name,
               scene_.source_file.empty() ? "built-in" : scene_.source_file, scene_.hash);
  on_every_rank([&] { world_ = build(scene_); });
  spdlog::info("mesh ({:.2f} s): {}", world_->mesh_seconds, format_quality(world_->mesh_quality));
  for (const auto& m : world_->models) spdlog::info("model: {}", m->name());
  if (split()) on_every_rank([&] { split_between_ranks(); });
  graph_ = std::make_unique<StepGraph>(world_->systems(), options_.threads, world_->plan.graph_periods());
  spdlog::info("the step, as the composition root scripts it:\n{}", world_->plan.script());
  check_background_access();
  if (options_.check_access) {
    // The check attributes every column lookup during a system's run to that system: work running beside
    // the graph would be counted against it.
    if (has_background_)
      throw Error(
          "RunOptions::check_access: this run has work beside the step graph (fluid_solid.coupling: "
          "concurrent), whose column lookups the check would blame on the graph's systems; check the "
          "scene with the sequential coupling");
    graph_->check_access_against(&world_->store);
  }
  on_every_rank([&] { choose_dt(); });
  on_every_rank([&] {
    if (writes_ && !options_.restart_latest) refuse_or_clear_earlier_run();
  });
  if (options_.write_output)
    checkpoints_ = std::make_unique<CheckpointSet>(options_.out_dir, scene_.checkpoint.keep);
  // A restart reads what it continues (checkpoint, time series) before anything in the folder changes, so
  // a refused restart leaves the interrupted run's files as they were. Every rank of a job reads it.
  if (options_.restart_latest) on_every_rank([&] { restart_from_latest(); });
  if (writes_) {
    create_output_dir(options_.out_dir);
    open_log_file(options_.out_dir / "rift.log");
    write_text_atomic(options_.out_dir / "scene.yaml", scene_.resolved_yaml);
    series_ = std::make_unique<XdmfSeries>(options_.out_dir, "rift");
    remove_killed_writers_files();
    if (options_.restart_latest) series_->resume(time());
  }
}

namespace {

// "a, b, c and 4 more": the first `shown` of a list for a message (an empty name reads "the whole scene").
std::string some_names(const std::vector<std::string>& names, size_t shown) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < shown; ++i)
    out += (i ? ", " : "") + (names[i].empty() ? std::string("the whole scene") : names[i]);
  if (names.size() > shown) out += fmt::format(" and {} more", names.size() - shown);
  return out;
}

}  // namespace

// A new run never mixes its files with an earlier run's (a longer run's later outputs would stay beside
// the new ones, and its checkpoints would be taken for this run's): the folder is refused, or, with
// overwrite, the earlier run's files (Rift's names only) are deleted first.
void RunLoop::refuse_or_clear_earlier_run() {
  const std::vector<std::string> earlier = earlier_run_files(options_.out_dir);
  if (earlier.empty()) return;
  const std::string named = some_names(earlier, 5);
  if (!options_.overwrite)
    throw Error("output folder " + options_.out_dir.string() + " holds an earlier run (" + named +
                "): continue it with --restart latest, write elsewhere with --out, or replace it with "
                "--overwrite (deletes that run's files only)");
  remove_earlier_run(options_.out_dir);
  spdlog::info("--overwrite: removed the earlier run in {} ({})", options_.out_dir.string(), named);
}

// A run killed while writing leaves "<output>.tmp-<pid>" files; the next run in the folder deletes those
// of its own outputs (never checkpoints' here: CheckpointSet prunes its folder).
void RunLoop::remove_killed_writers_files() {
  static constexpr std::string_view kRunFiles[] = {"scene.yaml", "timeseries.csv", "summary.json",
                                                   "fractures.csv"};
  const auto removed = remove_orphan_temp_files(options_.out_dir, [&](std::string_view name) {
    return std::find(std::begin(kRunFiles), std::end(kRunFiles), name) != std::end(kRunFiles) ||
           series_->is_own_file_name(name);
  });
  if (!removed.empty())
    spdlog::warn("removed {} temporary file(s) a killed run left in {}: {}", removed.size(),
                 options_.out_dir.string(), fmt::join(removed, ", "));
}

RunLoop::~RunLoop() {
  join_background_quietly();  // before the graph's arena and the world go
  if (writes_) close_log_file();
}

// Work a stage runs beside the graph (engine/schedule/step_plan.hpp) overlaps every system of the graph, so
// no system may write a column that work touches or read one it writes: checked once, from the declared
// access, the same rule the graph orders its own systems by.
void RunLoop::check_background_access() {
  for (const StepStage& stage : world_->plan.stages()) {
    if (stage.kind != StepStage::Kind::beside) continue;
    has_background_ = true;
    const Access background = stage.work->access();
    for (System* s : world_->systems()) {
      const std::string column = access_conflict(background, s->access());
      if (!column.empty())
        throw Error("internal: the step stage '" + stage.name + "' beside the graph and the system " +
                    s->name() + " both use " + column + " at the same time; report this with the scene");
    }
  }
}

void RunLoop::join_background() {
  if (!has_background_) return;
  graph_->in_arena([&] {
    for (BackgroundWork* work : world_->plan.background()) work->join();
  });
}

void RunLoop::join_background_quietly() noexcept {
  try {
    join_background();
  } catch (const std::exception& e) {  // already stopping; the first error is the one reported
    spdlog::debug("while stopping: {}", e.what());
  }
}

// The step count comes from a division of two doubles: beyond 2^53 the double no longer holds every
// integer, and beyond int64's range the cast is undefined (it came back as one step of time.end, a run
// that said `completed` after a single step far above its stable one). Such a run could not finish in any
// case: it is refused with the figures that make it so.
void RunLoop::check_step_count(double steps, double dt, const std::string& source) const {
  constexpr double kMostSteps = 9007199254740992.0;  // 2^53
  if (std::isfinite(steps) && steps >= 0.0 && steps <= kMostSteps) return;
  throw Error(fmt::format(
      "time.end = {:.6g} s in steps of {:.6g} s ({}) is {:.6g} steps, more than a run can count (2^53) or "
      "finish. Likely cause: a degenerate element (a flat or sliver tet, a near-zero volume) or an extreme "
      "material or penalty value makes the stable step tiny, or time.dt is far too small. What to change: "
      "check the mesh (rift check), the materials and time.dt.",
      scene_.time.end, dt, source, steps));
}

void RunLoop::choose_dt() {
  const double stable = world_->stable_dt();
  const TimeSpec& t = scene_.time;
  // A model with its own step (the fluid's fluid.dt) fixes the run's: t = step x that dt exactly.
  for (const auto& m : world_->models) {
    const std::optional<double> fixed = m->required_dt();
    if (!fixed) continue;
    if (t.dt && std::abs(*t.dt - *fixed) > 1e-12 * *fixed)
      throw Error(
          fmt::format("time.dt = {:.17g} s disagrees with the {} step {:.17g} s ({}.dt). Remove "
                      "time.dt (the {} step is the run's), or make them equal.",
                      *t.dt, m->name(), *fixed, m->name(), m->name()));
    if (*fixed > stable && !t.allow_unstable_dt)
      throw Error(
          fmt::format("{}.dt = {:.6g} s is above the stable step {:.6g} s of another model in the run",
                      m->name(), *fixed, stable));
    const double n = t.end / *fixed;
    check_step_count(n, *fixed, fmt::format("{}.dt", m->name()));
    total_steps_ = std::max<int64_t>(1, static_cast<int64_t>(std::llround(n)));
    if (std::abs(n - static_cast<double>(total_steps_)) > 1e-6 * n)
      throw Error(
          fmt::format("time.end = {:.6g} s is not a whole number of {} steps of {:.6g} s ({}.dt): "
                      "{:.6g} steps. Make time.end a multiple of {}.dt, e.g. {:.6g} s.",
                      t.end, m->name(), *fixed, m->name(), n, m->name(), std::ceil(n) * *fixed));
    dt_ = *fixed;
    spdlog::info("dt = {:.6g} s ({}.dt), {} steps to t = {:.6g} s, {} thread(s)", dt_, m->name(),
                 total_steps_, static_cast<double>(total_steps_) * dt_, options_.threads);
    return;
  }
  double requested;
  if (t.dt) {
    requested = *t.dt;
    if (requested > stable && !t.allow_unstable_dt)
      throw Error(fmt::format(
          "time.dt = {:.6g} s is above the stable step {:.6g} s of this mesh and material (ratio {:.3g}). "
          "Lower time.dt (or remove it to use time.safety x the stable step), or set time.allow_unstable_dt: "
          "true to run it on purpose.",
          requested, stable, requested / stable));
    if (requested > stable)
      spdlog::warn("time.dt = {:.6g} s exceeds the stable step {:.6g} s (allowed by the scene)", requested,
                   stable);
  } else {
    if (!std::isfinite(stable))
      throw Error("time.dt: the scene has no model that sets a stable step, so time.dt must be given");
    requested = t.safety * stable;
  }
  // Whole steps that land exactly on the end time: dt never exceeds the requested one.
  check_step_count(
      t.end / requested, requested,
      t.dt ? std::string("time.dt") : fmt::format("time.safety x the stable step {:.6g} s", stable));
  total_steps_ = static_cast<int64_t>(std::ceil(t.end / requested - 1e-9));
  total_steps_ = std::max<int64_t>(total_steps_, 1);
  dt_ = t.end / static_cast<double>(total_steps_);
  if (dt_ > requested * (1.0 + 1e-9))  // the promise behind `completed`: no step above the one asked for
    throw Error(fmt::format("internal error: {} steps of {:.17g} s to t = {:.6g} s exceed the step {:.17g} s",
                            total_steps_, dt_, t.end, requested));
  spdlog::info("dt = {:.6g} s (stable {:.6g} s), {} steps to t = {:.6g} s, {} thread(s)", dt_, stable,
               total_steps_, t.end, options_.threads);
}

// A checkpoint that cannot be read as one (truncated, foreign, another format, a checksum that fails) is
// damage: the restart warns and takes the previous one. An intact checkpoint that does not fit this run
// (another scene, dt, tables) is refused at once: the older ones of the same run would not fit either.
void RunLoop::restart_from_latest() {
  if (!checkpoints_) throw Error("--restart needs an output folder");
  std::vector<CheckpointProblem> skipped;
  const auto latest = checkpoints_->latest(&skipped);
  for (const CheckpointProblem& p : skipped)
    spdlog::warn("--restart latest: skipping {}: {}", p.file.string(), p.reason);
  if (!latest) {
    std::string message = "--restart latest: no intact checkpoint in " + checkpoints_->dir().string();
    for (const CheckpointProblem& p : skipped) message += "\n  " + p.file.string() + ": " + p.reason;
    throw Error(message + "\nRun without --restart, or point --out at the folder of the interrupted run");
  }
  const CheckpointMeta meta = read_checkpoint(*latest, world_->store);
  bool extending = false;
  if (meta.scene_hash != scene_.hash) {
    // Only the end time or the output settings changed: the run continues to the new end.
    const std::vector<std::string> keys = differing_keys(meta.resolved_scene, scene_.resolved_yaml);
    extending = only_extension_keys(keys);
    if (!extending) {
      const std::string named = some_names(keys, 12);
      throw Error("--restart latest: " + latest->string() + " was written for scene hash " + meta.scene_hash +
                  ", this scene resolves to " + scene_.hash + "; they differ in " + named +
                  ". A restart continues the same scene; it may change only time.end and output.* (to extend "
                  "or re-plan the outputs of a run). Compare " +
                  (options_.out_dir / "scene.yaml").string() + " with your scene and overrides.");
    }
  }
  if (meta.dt != dt_) {
    if (!extending)
      throw Error(fmt::format("--restart latest: checkpoint dt {:.17g} s differs from this run's {:.17g} s",
                              meta.dt, dt_));
    // An extended run keeps the steps it took: the same dt, as many steps as reach the new end.
    if (!(meta.dt <= dt_ * (1.0 + 1e-6) || scene_.time.allow_unstable_dt))
      throw Error(fmt::format("--restart latest: the run's step {:.17g} s is above this scene's {:.17g} s",
                              meta.dt, dt_));
    dt_ = meta.dt;
    total_steps_ = static_cast<int64_t>(std::ceil(scene_.time.end / dt_ - 1e-9));
  }
  if (meta.step > total_steps_)
    throw Error(
        fmt::format("--restart latest: the checkpoint is at t = {:.6g} s (step {}), beyond time.end = "
                    "{:.6g} s: give a later time.end to extend the run",
                    meta.time, meta.step, scene_.time.end));
  if (extending)
    spdlog::info(
        "extending the run to t = {:.6g} s: {} steps of {:.6g} s (only time.end or output.* changed)",
        static_cast<double>(total_steps_) * dt_, total_steps_, dt_);
  step_ = meta.step;
  for (const auto& m : world_->models) m->restored(StepContext{step_, time(), dt_});
  outputs_written_ = meta.integers.count("outputs_written") ? meta.integers.at("outputs_written") : 0;
  // The rows up to the restart step continue into the rewritten time series.
  try {
    metric_rows_ = read_time_series(options_.out_dir / "timeseries.csv", step_);
  } catch (const Error& e) {
    throw Error(std::string("--restart latest: ") + e.what() +
                ". The restart carries that file's rows on into the continued run: repair the line, or move "
                "the file away to continue without the earlier rows.");
  }
  spdlog::info("restarted from {} at step {}, t = {:.6g} s", latest->string(), step_, time());
}

namespace {

// Fault injection for the crash tests (tests/slow/test_faults.cpp, docs/reliability.md): with
// RIFT_FAULT_KILL_AT_STEP=<n> in the environment the process kills itself with SIGKILL as it starts
// step n, between one step's outputs and the next: a moment in the middle of a run, chosen by the test.
void kill_at_step_if_asked(int64_t step) {
  static const long long kill_at = [] {
    const char* value = std::getenv("RIFT_FAULT_KILL_AT_STEP");
    return value ? std::strtoll(value, nullptr, 10) : 0LL;
  }();
  if (kill_at > 0 && step == kill_at) ::raise(SIGKILL);
}

}  // namespace

// The plan's stages around the graph at step `ctx`, inside the graph's arena when work runs beside the
// graph (its task must live there). Before the graph: each beside stage whose window starts here launches.
void RunLoop::start_windows(const StepContext& ctx) {
  in_stage_arena([&] {
    for (const StepStage& stage : world_->plan.stages())
      if (stage.kind == StepStage::Kind::beside && starts_window(stage.every, ctx)) stage.work->launch(ctx);
  });
}

// After the graph, in script order: each beside stage whose window ends here joins, and each after stage
// due runs.
void RunLoop::end_windows(const StepContext& ctx) {
  in_stage_arena([&] {
    for (const StepStage& stage : world_->plan.stages()) {
      if (stage.kind == StepStage::Kind::graph || !runs_at(stage.every, ctx)) continue;
      if (stage.kind == StepStage::Kind::beside)
        stage.work->join();
      else
        stage.run(ctx);
    }
  });
}

void RunLoop::step_once() {
  kill_at_step_if_asked(step_ + 1);
  const bool observed =
      observe_every_step_ || observe_next_ || (step_ + 1) % kObservedEvery == 0 || step_ + 1 == total_steps_;
  const StepContext ctx{step_, time(), dt_, false, observed};
  start_windows(ctx);
  graph_->run_step(ctx);
  ++step_;
  end_windows(ctx);
  const StepContext after{step_, time(), dt_, step_ == total_steps_};
  // Every guard that fires at this step is reported: one model's failure is often another's symptom (a
  // fluid step that does not converge while the coupling's force oscillates and grows).
  if (split())
    for (const auto& m : world_->models) m->finish_share_step(ctx);
  std::string stop;
  for (const auto& m : world_->models)
    if (auto diagnosis = m->check_health(after))
      stop += (stop.empty() ? "run stopped by the " : "\nAt the same step, the ") + m->name() +
              " guard: " + *diagnosis;
  if (!split()) {
    if (!stop.empty()) throw Error(stop);
    return;
  }
  if (const auto agreed = agree_on_stop(stop.empty() ? std::nullopt : std::optional<std::string>(stop)))
    throw JobError(*agreed);
}

RunResult RunLoop::run() {
  const auto t0 = clock_type::now();
  RunResult result;
  Progress progress(total_steps_, scene_.time.end, options_.progress && job_rank_ == 0);
  const double interval = scene_.output.interval;
  const int64_t metric_every = std::max<int64_t>(1, total_steps_ / 1000);
  auto last_checkpoint = clock_type::now();
  if (step_ == 0 && options_.write_output) {
    record_metrics();
    write_output();
  }
  // The loop knows which steps it reads after (outputs, metrics, a planned stop): only those compute the
  // derived fields (StepContext::observed). A checkpoint may hold older derived fields: nothing reads them
  // before an observed step rewrites them, so a restart continues with the same bits.
  observe_every_step_ = false;
  try {
    while (step_ < total_steps_) {
      const int64_t next = step_ + 1;
      observe_next_ =
          (options_.write_output &&
           (next % metric_every == 0 ||
            (interval > 0 && static_cast<double>(next) * dt_ >=
                                 static_cast<double>(outputs_written_) * interval * (1 - 1e-12)))) ||
          (options_.stop_after_step && next >= *options_.stop_after_step);
      step_once();
      const bool last = step_ == total_steps_;
      if (options_.write_output) {
        if (step_ % metric_every == 0 || last) record_metrics();
        const bool output_due =
            interval > 0 && time() >= static_cast<double>(outputs_written_) * interval * (1 - 1e-12);
        if (output_due || last) write_output();
        const CheckpointSpec& c = scene_.checkpoint;
        const bool stop_here = options_.stop_after_step && step_ >= *options_.stop_after_step && !last;
        // The clock and a signal are rank 0's in a split run: every rank checkpoints and stops with it.
        const unsigned rank_zero = agree_with_rank_zero(
            (interrupt_flag().load() ? 1u : 0u) |
            (c.every_seconds > 0 && seconds_since(last_checkpoint) >= c.every_seconds ? 2u : 0u));
        const bool interrupted = rank_zero & 1u;
        if ((c.every_steps > 0 && step_ % c.every_steps == 0) || (rank_zero & 2u) || stop_here ||
            interrupted) {
          write_checkpoint();
          last_checkpoint = clock_type::now();
        }
        if (interrupted || stop_here) {
          result.stop_reason = interrupted ? "signal" : "stop_after_step";
          spdlog::warn("stopped at step {} (t = {:.6g} s) by {}; continue with --restart latest", step_,
                       time(), interrupted ? "a signal" : "--stop-after");
          break;
        }
      } else if (options_.stop_after_step && step_ >= *options_.stop_after_step) {
        result.stop_reason = "stop_after_step";
        break;
      }
      progress.update(step_, time(), progress_quantities_);
    }
  } catch (const Error& e) {
    // One rank's error in a split run: the others are waiting for it, and the job ends (the CLI).
    if (split() && !dynamic_cast<const JobError*>(&e)) throw;
    observe_every_step_ = true;
    join_background_quietly();
    progress.finish();
    result.steps = step_;
    result.time = time();
    result.wall_seconds = seconds_since(t0);
    result.stop_reason = e.what();
    if (options_.write_output) {
      gather_to_root();
      write_time_series();
      write_summary(result);
    }
    throw;
  }
  observe_every_step_ = true;
  join_background();  // a run stopped mid-window: the state hashed is the joined one, as a checkpoint's
  progress.finish();
  result.steps = step_;
  result.time = time();
  result.completed = step_ == total_steps_;
  result.state_hash = run_state_hash();
  result.wall_seconds = seconds_since(t0);
  if (options_.write_output) write_summary(result);
  log_timing_table();
  spdlog::info("{} at step {} (t = {:.6g} s) in {:.2f} s, state hash {}",
               result.completed ? "finished" : "stopped", step_, time(), result.wall_seconds,
               hex64(result.state_hash));
  return result;
}

namespace {

// NaN or infinity never reaches a file: a value the guards let through (a derived field overflowing before
// the state does) stops the run here, naming it, and the output is not written.
[[noreturn]] void refuse_non_finite(const std::string& what, int64_t step, double time) {
  throw Error(fmt::format(
      "run stopped at step {} (t = {:.6g} s): {} is not finite, so the output was not written. Likely "
      "cause: a load or material value beyond what the solver carries in double precision, or an "
      "instability the guards had not yet caught. What to change: check the loads and material values, or "
      "reduce time.safety",
      step, time, what));
}

void check_finite(std::span<const XdmfGrid> grids, int64_t step, double time) {
  for (const XdmfGrid& g : grids) {
    for (size_t i = 0; i < 3 * g.point_count; ++i)
      if (!std::isfinite(g.points[i]))
        refuse_non_finite(fmt::format("the {} grid's point {}", g.name, i / 3), step, time);
    for (const XdmfField& f : g.fields) {
      if (f.type != ElementType::f64) continue;
      const auto* v = static_cast<const double*>(f.data);
      for (size_t i = 0; i < f.rows * static_cast<size_t>(f.components); ++i)
        if (!std::isfinite(v[i]))
          refuse_non_finite(fmt::format("field '{}' of the {} grid at row {}", f.name, g.name,
                                        i / static_cast<size_t>(f.components)),
                            step, time);
    }
  }
}

}  // namespace

void RunLoop::write_output() {
  const auto t0 = clock_type::now();
  gather_to_root();
  on_every_rank([&] {
    if (!writes_) return;
    std::vector<XdmfGrid> grids;
    for (const auto& m : world_->models) m->output_grids(grids, scene_.output.fields);
    check_finite(grids, step_, time());
    if (!grids.empty()) series_->write(time(), step_, grids);
    write_time_series();
  });
  ++outputs_written_;
  output_seconds_ += seconds_since(t0);
}

namespace {

// What the progress line shows beside the step: the scene's key quantities from the latest metrics row
// (values[0], values[1] are step and time), those the run has.
std::string key_quantities(const std::vector<std::string>& names, const std::vector<double>& values) {
  struct Shown {
    const char* name;
    const char* format;
    double scale;  // to the unit in the format
  };
  static constexpr Shown kShown[] = {
      {"solid_broken_joints", "broken {:.0f}", 1.0},
      {"flow_well_pressure", "well {:.4g} MPa", 1e-6},
      {"fluid_solid_inlet_pressure", "inlet {:.4g} MPa", 1e-6},
      {"fluid_pressure_max", "fluid p max {:.4g} MPa", 1e-6},
  };
  std::string out;
  for (const Shown& q : kShown)
    for (size_t i = 0; i < names.size() && i + 2 < values.size(); ++i)
      if (names[i] == q.name)
        out += (out.empty() ? "" : ", ") + fmt::format(fmt::runtime(q.format), values[i + 2] * q.scale);
  return out;
}

}  // namespace

// In a split run every rank computes the row (the energies are added over the ranks); rank 0's, from the
// gathered store, is the run's.
void RunLoop::record_metrics() {
  gather_to_root();
  std::vector<std::pair<std::string, double>> row;
  for (const auto& m : world_->models) m->metrics(time(), row);
  if (metric_names_.empty())
    for (const auto& [name, value] : row) metric_names_.push_back(name);
  std::vector<double> values{static_cast<double>(step_), time()};
  on_every_rank([&] {
    for (const auto& [name, value] : row)
      if (job_rank_ == 0 && !std::isfinite(value))
        refuse_non_finite("the time series' " + name, step_, time());
  });
  for (const auto& [name, value] : row) values.push_back(value);
  progress_quantities_ = key_quantities(metric_names_, values);
  metric_rows_.push_back(std::move(values));
}

// The time series is rewritten (atomically) with each field output and checkpoint, not on every
// metrics row: an fsync per step would dominate small runs.
void RunLoop::write_time_series() const {
  if (!writes_) return;
  write_text_atomic(options_.out_dir / "timeseries.csv", format_time_series(metric_names_, metric_rows_));
  for (const auto& m : world_->models) m->write_logs(options_.out_dir);
}

void RunLoop::write_checkpoint() {
  // Everything a model runs beside the step ends first: a checkpoint is the store at rest.
  join_background();
  const auto t0 = clock_type::now();
  gather_to_root();
  if (!writes_) return;
  CheckpointMeta meta;
  meta.step = step_;
  meta.time = time();
  meta.dt = dt_;
  meta.scene_hash = scene_.hash;
  meta.resolved_scene = scene_.resolved_yaml;
  meta.rift_version = build::version;
  meta.integers["outputs_written"] = outputs_written_;
  write_time_series();
  const auto file = checkpoints_->write(world_->store, meta);
  checkpoint_seconds_ += seconds_since(t0);
  spdlog::debug("checkpoint {}", file.string());
}

// Every rank of a split run builds the summary (a model's figures may be sums over the ranks); rank 0
// writes it.
void RunLoop::write_summary(const RunResult& result) const {
  RunSummary summary;
  auto& j = summary.root();
  j["rift_version"] = build::version;
  j["scene"] = {{"name", scene_.name}, {"file", scene_.source_file}, {"hash", scene_.hash}};
  j["status"] =
      result.completed ? "completed" : (result.stop_reason.empty() ? "stopped" : result.stop_reason);
  j["threads"] = options_.threads;
  j["ranks"] = job_size_;
  if (split()) j["partition"] = partition_summary_;
  j["steps"] = result.steps;
  j["total_steps"] = total_steps_;
  j["simulated_time"] = result.time;
  j["dt"] = dt_;
  j["stable_dt"] = world_->stable_dt();
  j["wall_seconds"] = result.wall_seconds;
  j["state_hash"] = hex64(result.state_hash);
  j["mesh"] = quality_to_json(world_->mesh_quality);
  j["mesh"]["seconds"] = world_->mesh_seconds;
  for (const auto& t : graph_->timings()) j["wall_seconds_per_system"][t.name] = t.seconds;
  for (const auto& m : world_->models)
    for (const auto& t : m->timings()) j["wall_seconds_per_system"][t.name] = t.seconds;
  j["wall_seconds_per_system"]["output"] = output_seconds_;
  j["wall_seconds_per_system"]["checkpoint"] = checkpoint_seconds_;
  for (const auto& m : world_->models) m->summarize(j["metrics"]);
  if (writes_) summary.write(options_.out_dir / "summary.json");
}

void RunLoop::log_timing_table() const {
  // Work beside the graph (the concurrent fluid step) overlaps it: it is listed, not added to the total.
  double total = output_seconds_ + checkpoint_seconds_;
  for (const auto& t : graph_->timings()) total += t.seconds;
  std::string table =
      fmt::format("{:<22} {:>10} {:>8} {:>12}\n", "system", "wall [s]", "share", "per call [us]");
  auto row = [&](const std::string& name, double s, int64_t calls) {
    table += fmt::format("{:<22} {:>10.3f} {:>7.1f}% {:>12.2f}\n", name, s, total > 0 ? 100 * s / total : 0.0,
                         calls > 0 ? 1e6 * s / calls : 0.0);
  };
  for (const auto& t : graph_->timings()) row(t.name, t.seconds, t.calls);
  for (const auto& m : world_->models)
    for (const auto& t : m->timings()) row(t.name, t.seconds, t.calls);
  row("output", output_seconds_, outputs_written_);
  row("checkpoint", checkpoint_seconds_, 0);
  spdlog::info("wall time per system:\n{}", table);
}

}  // namespace rift
