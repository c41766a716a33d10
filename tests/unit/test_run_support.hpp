#pragma once
// One run of a scene into a folder, as `rift run` does it (no progress line): for the tests of runs,
// restarts and outputs.
#include <cstdint>
#include <filesystem>
#include <optional>

#include "systems/simulation.hpp"

namespace rift::test {

// Options of a run in memory: no output folder, no progress line.
inline RunOptions quiet_options(int threads = 1) {
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  o.threads = threads;
  return o;
}

inline RunResult run_scene(const Scene& scene, const std::filesystem::path& dir, int threads,
                           std::optional<int64_t> stop = {}, bool restart = false) {
  RunOptions o;
  o.out_dir = dir;
  o.threads = threads;
  o.progress = false;
  o.stop_after_step = stop;
  o.restart_latest = restart;
  return Simulation(scene, o).run();
}

// A run stopped after step `stop` (it leaves a checkpoint), then continued with --restart latest.
struct StoppedAndResumed {
  RunResult first, rest;
};
inline StoppedAndResumed stop_and_resume(const Scene& scene, const std::filesystem::path& dir, int threads,
                                         int64_t stop) {
  RunResult first = run_scene(scene, dir, threads, stop);
  return {first, run_scene(scene, dir, threads, std::nullopt, true)};
}

}  // namespace rift::test
