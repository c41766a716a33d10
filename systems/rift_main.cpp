// rift: the program. The command line and its subcommands are the engine's (engine/cli/commands.cpp);
// the scenes' worlds are built by the composition root (systems/world_builder.hpp), handed to them here.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <new>

#include "engine/cli/commands.hpp"
#include "engine/distributed/mpi_runtime.hpp"
#include "systems/world_builder.hpp"

int main(int argc, char** argv) {
  using namespace rift::cli;
  using rift::build_world;
  CLI::App app{"Rift: fluid-driven fracture in rock (FEMDEM solid, implicit fluid).", "rift"};
  app.require_subcommand(1);

  RunArgs run_args;
  auto* run_cmd = app.add_subcommand("run", "Run a scene (the built-in default scene when none is given)");
  run_cmd->add_option("scene", run_args.scene.scene, "scene file (YAML)");
  run_cmd->add_option("--out,-o", run_args.out_dir, "output folder (default rift-out/<scene name>)");
  run_cmd->add_option("--set", run_args.scene.overrides,
                      "override a scene value: key.path=value (repeatable)");
  run_cmd->add_option("--threads,-j", run_args.threads, "worker threads")->check(CLI::Range(1, 1024));
  run_cmd->add_option("--restart", run_args.restart, "continue from a checkpoint: 'latest'");
  run_cmd->add_option("--stop-after", run_args.stop_after, "stop after this step, writing a checkpoint");
  run_cmd->add_flag("--quiet,-q", run_args.quiet, "only warnings and errors");
  run_cmd->add_flag("--overwrite", run_args.overwrite,
                    "replace an earlier run in the output folder (its files only; others stay)");

  SceneArgs check_args;
  auto* check_cmd = app.add_subcommand("check", "Validate a scene and print it fully resolved");
  check_cmd->add_option("scene", check_args.scene, "scene file (YAML)");
  check_cmd->add_option("--set", check_args.overrides, "override a scene value: key.path=value (repeatable)");

  auto* info_cmd = app.add_subcommand("info", "Versions of Rift and its libraries, build flags");

  SceneArgs graph_args;
  int graph_threads = 1;
  auto* graph_cmd = app.add_subcommand(
      "graph", "Print the step: its script of stages (a DOT comment), then its task graph as Graphviz DOT");
  graph_cmd->add_option("scene", graph_args.scene, "scene file (YAML)");
  graph_cmd->add_option("--set", graph_args.overrides, "override a scene value (repeatable)");
  graph_cmd->add_option("--threads,-j", graph_threads, "worker threads")->check(CLI::Range(1, 1024));

  PartitionArgs partition_args;
  auto* partition_cmd = app.add_subcommand(
      "partition", "How a scene's solid splits across processes: METIS parts, halo, predicted efficiency");
  partition_cmd->add_option("scene", partition_args.scene.scene, "scene file (YAML)");
  partition_cmd->add_option("--set", partition_args.scene.overrides, "override a scene value (repeatable)");
  partition_cmd
      ->add_option("--ranks,-n", partition_args.ranks, "rank counts, e.g. 2,4,64 (default 2,4,8,16,64)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1 << 24));
  partition_cmd->add_option("--latency", partition_args.latency_us, "network latency per message, us (1.5)");
  partition_cmd->add_option("--bandwidth", partition_args.bandwidth_gbs,
                            "bandwidth of a rank's link, GB/s (12.5)");
  partition_cmd->add_option("--json", partition_args.json_out, "also write the reports to this JSON file");

  SweepArgs sweep_args;
  auto* sweep_cmd = app.add_subcommand(
      "sweep", "Run a scene's variants and record wall time against error (docs/speed-accuracy.md)");
  sweep_cmd->add_option("scene", sweep_args.scene.scene, "scene file (YAML)")->required();
  sweep_cmd->add_option("--vary", sweep_args.vary, "key.path=v1,v2,... (repeatable: every combination runs)")
      ->required();
  sweep_cmd->add_option("--set", sweep_args.scene.overrides, "override a scene value in every variant");
  sweep_cmd->add_option("--out,-o", sweep_args.out_dir,
                        "output folder (default rift-out/sweep-<scene name>)");
  sweep_cmd->add_option("--threads,-j", sweep_args.threads, "worker threads")->check(CLI::Range(1, 1024));

  std::string plot_dir, plot_out;
  auto* plot_cmd =
      app.add_subcommand("plot", "PNGs of a run's time series (energies, loads, fracture, fluid)");
  plot_cmd->add_option("run", plot_dir, "a run's output folder (with timeseries.csv)")->required();
  plot_cmd->add_option("--out,-o", plot_out, "folder for the pictures (default RUN/plots)");

  std::string render_dir;
  rift::RenderOptions render_options;
  auto* render_cmd = app.add_subcommand(
      "render", "Field pictures of a run, drawn headless by ParaView: a cut coloured by a field, the cracks");
  render_cmd->add_option("run", render_dir, "a run's output folder (with rift.series.json)")->required();
  render_cmd->add_option("--out,-o", render_options.out_dir,
                         "folder for the pictures (default RUN/pictures)");
  render_cmd->add_option(
      "--field", render_options.field,
      "NAME[:COMPONENT], e.g. stress:yy, principal_stress:max (default), velocity:magnitude");
  render_cmd
      ->add_option("--normal", render_options.normal, "axis normal to the cut plane: x, y or z (default)")
      ->check(CLI::IsMember({"x", "y", "z"}));
  render_cmd->add_option("--at", render_options.at,
                         "the cut plane's position along its normal, m (default: centre)");
  render_cmd->add_option("--times", render_options.times,
                         "'last' (default), 'all', or times in s separated by commas (nearest outputs)");
  render_cmd->add_option("--size", render_options.size, "picture size WIDTHxHEIGHT (default 1280x960)");
  render_cmd->add_option("--range", render_options.range,
                         "MIN,MAX of the colour map in display units (default: 1st-99th percentile)");
  std::string schema_out;
  auto* schema_cmd = app.add_subcommand(
      "schema", "Print the scene format's JSON Schema (for editors: docs/scene-format.md, Editor support)");
  schema_cmd->add_option("--out,-o", schema_out, "write it to this file instead (replaced atomically)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  // `rift run` splits a scene between the ranks of a job (docs/distributed.md); the other commands would
  // run once per rank, each writing the same files. Refused before anything is written, said once: rank 0
  // says it and ends the job with status 2; the others end with 0 so that mpirun does not cut rank 0 off
  // before it has said it.
  if (const rift::MpiRank job = rift::launched_rank(); job.size > 1 && !*info_cmd && !*run_cmd) {
    if (job.rank != 0) return 0;
    std::cerr << "rift: this is a job of " << job.size << " processes (mpirun -np " << job.size
              << "); only `rift run` splits a scene between processes: run this command without mpirun. "
                 "`rift partition SCENE --ranks "
              << job.size << "` shows how the scene would split across " << job.size << " ranks.\n";
    return 2;
  }
  // The commands report what a user or a run can run into (rift::Error) themselves. Anything else is a
  // defect of Rift: it still ends with a message and exit 1, not an abort.
  try {
    if (*run_cmd) return run(run_args, build_world);
    if (*check_cmd) return check(check_args, build_world);
    if (*info_cmd) return info();
    if (*graph_cmd) return graph(graph_args, graph_threads, build_world);
    if (*partition_cmd) return partition(partition_args, build_world);
    if (*sweep_cmd) return sweep(sweep_args, build_world);
    if (*plot_cmd) return plot(plot_dir, plot_out);
    if (*render_cmd) return render(render_dir, render_options);
    if (*schema_cmd) return schema(schema_out);
  } catch (const std::bad_alloc&) {
    std::cerr << "rift: internal error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "rift: internal error: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "rift: internal error: an exception of unknown type\n";
    return 1;
  }
  return 2;
}
