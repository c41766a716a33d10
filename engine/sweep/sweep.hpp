#pragma once
// rift sweep: the speed-accuracy trade of one scene, measured. Runs every combination of the values
// given per key (--vary key.path=v1,v2,...; the first key varies slowest), each into its own folder
// out/vNNN, and records per variant the end-to-end wall time (mesh, set-up and run), steps, tets and the
// scene's error metrics (`reference` section): against the analytic value where the scene gives one,
// else against the finest variant (most steps x tets). Then marks the Pareto front (no other variant
// both faster and more accurate) and writes
//   out/sweep.csv    one row per variant
//   out/sweep.json   the sweep's definition and its rows (what a resumed sweep reads)
//   out/sweep.png    error against wall time, front marked (python3 with matplotlib; see the README)
// Resume: run the same command again. Finished variants are kept; an interrupted one runs again from
// its start, so every wall time is that of one uninterrupted run.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/world.hpp"

namespace rift {

struct SweepAxis {
  std::string key;  // a scene key path, as for --set
  std::vector<std::string> values;
};

// "key.path=v1,v2,..." (brackets kept whole: "direction=[0,0,1],[0,1,0]"). Throws rift::Error.
SweepAxis parse_sweep_axis(const std::string& text);

struct SweepOptions {
  std::string scene_path;
  std::vector<std::string> overrides;  // --set, applied to every variant before its own values
  std::vector<SweepAxis> axes;
  std::filesystem::path out_dir;
  int threads = 1;
  bool plot = true;
  WorldBuilder build_world;  // the composition root's (systems/world_builder.hpp)
};

struct SweepRow {
  int index = 0;
  std::vector<std::string> values;  // one per axis
  std::string status;               // "done", or "failed: <diagnosis>"
  double wall_seconds = 0.0;
  int64_t steps = 0, tets = 0;
  std::vector<std::optional<double>> metrics, errors;  // one per reference metric
  std::optional<double> error;                         // the largest of the errors
  bool pareto = false;
};

struct SweepResult {
  std::vector<std::string> metric_names;
  std::vector<SweepRow> rows;  // the variants done so far, in variant order
  size_t ran = 0;              // variants run by this call (the others were resumed from out/)
  bool interrupted = false;    // SIGINT/SIGTERM: the rest is left for a resumed sweep
  std::string plot_note;       // what happened to the PNG
};

// Throws rift::Error for a bad scene or axis, or an out folder that holds a different sweep.
SweepResult run_sweep(const SweepOptions& options);

}  // namespace rift
