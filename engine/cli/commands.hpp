#pragma once
// The subcommands behind `rift`: run, check, info, graph, partition, sweep, plot, render, schema. Each
// returns the process exit code: 0 success, 1 a run that stopped with a diagnosis, 2 bad input (scene, mesh,
// options), 130 stopped by a signal (a checkpoint was written; continue with --restart latest).
#include <optional>
#include <string>
#include <vector>

#include "engine/render/run_render.hpp"
#include "engine/world.hpp"

namespace rift::cli {

struct SceneArgs {
  std::string scene;                   // path; empty: the built-in default scene
  std::vector<std::string> overrides;  // --set key.path=value
};

struct RunArgs {
  SceneArgs scene;
  std::string out_dir;  // empty: rift-out/<scene name>
  int threads = 1;
  std::string restart;                  // "" or "latest"
  std::optional<long long> stop_after;  // stop after this step with a checkpoint
  bool quiet = false;
  bool overwrite = false;  // replace an earlier run in the output folder
};

struct PartitionArgs {
  SceneArgs scene;
  std::vector<int> ranks{2, 4, 8, 16, 64};
  double latency_us = 1.5;  // the network model's (engine/partition_report.hpp)
  double bandwidth_gbs = 12.5;
  std::string json_out;  // empty: no JSON file
};

struct SweepArgs {
  SceneArgs scene;
  std::vector<std::string> vary;  // key.path=v1,v2,...
  std::string out_dir;            // empty: rift-out/sweep-<scene name>
  int threads = 1;
};

// build: the composition root's world builder (systems/world_builder.hpp), handed in by the program's entry
// (systems/rift_main.cpp): the CLI runs scenes without knowing their physics.
int run(const RunArgs& args, const WorldBuilder& build);
int sweep(const SweepArgs& args, const WorldBuilder& build);
int check(const SceneArgs& args, const WorldBuilder& build);
int info();
int graph(const SceneArgs& args, int threads, const WorldBuilder& build);
// rift partition SCENE --ranks 2,4,...: how the scene's solid splits across processes, the halo each rank
// exchanges and the efficiency that predicts on a stated network (engine/partition_report.hpp).
int partition(const PartitionArgs& args, const WorldBuilder& build);
// rift plot RUN_DIR [--out DIR]: PNGs of the run's time series (engine/plot/run_plot.hpp).
int plot(const std::string& run_dir, const std::string& out_dir);
// rift render RUN_DIR [options]: field pictures drawn by ParaView (engine/render/run_render.hpp).
int render(const std::string& run_dir, const RenderOptions& options);
// rift schema [--out FILE]: the scene format's JSON Schema (engine/scene/scene_schema.hpp) on standard
// output, or written atomically to FILE.
int schema(const std::string& out_file);

}  // namespace rift::cli
