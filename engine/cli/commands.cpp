#include "engine/cli/commands.hpp"

#include <CGAL/version.h>
#include <H5public.h>
#include <HYPRE_config.h>
#include <fmt/format.h>
#include <metis.h>
#include <mpi.h>
#include <oneapi/tbb/version.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/core/folder_name.hpp"
#include "engine/core/log.hpp"
#include "engine/distributed/job_agreement.hpp"
#include "engine/distributed/mpi_runtime.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/partition_report.hpp"
#include "engine/plot/run_plot.hpp"
#include "engine/run_loop.hpp"
#include "engine/run_report.hpp"
#include "engine/scene/load_scene.hpp"
#include "engine/scene/scene_schema.hpp"
#include "engine/sweep/reference_metrics.hpp"
#include "engine/sweep/sweep.hpp"
#include "rift/build_info.hpp"
#include "rift/default_scene.hpp"

namespace rift::cli {

namespace {

// The per-grid XDMF files a run wrote (rift_solid.xdmf, rift_fluid.xdmf, ...), in name order, each
// followed by a space: the ones ParaView opens one grid at a time.
std::string grid_files(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("rift_") && entry.path().extension() == ".xdmf") names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  std::string out;
  for (const auto& n : names) out += n + " ";
  return out;
}

// Reads the scene (or the built-in default); prints every diagnostic and returns nullopt on errors.
std::optional<Scene> read_scene(const SceneArgs& args) {
  SceneLoadResult r = args.scene.empty()
                          ? read_scene_text(default_scene_yaml, default_scene_name, ".", args.overrides)
                          : read_scene_file(args.scene, args.overrides);
  if (!r.errors.empty()) {
    for (const auto& d : r.errors) std::cerr << d.format() << "\n";
    std::cerr << r.errors.size() << " error(s) in " << (args.scene.empty() ? default_scene_name : args.scene)
              << "; nothing was run or written.\n";
    return std::nullopt;
  }
  return std::move(r.scene);
}

void on_signal(int) {
  RunLoop::interrupt_flag().store(true);
  // A second signal ends the process at once.
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

}  // namespace

// The physics and the whole wall time, from the summary the run wrote (nothing when there is none).
static void print_run_report(const std::filesystem::path& out_dir) {
  std::ifstream in(out_dir / "summary.json");
  if (!in) return;
  const auto summary = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!summary.is_discarded()) std::cout << run_report(summary);
}

int run(const RunArgs& args, const WorldBuilder& build) {
  // In a job of several ranks (mpirun), rank 0 speaks for the run: the others log errors only, and an
  // error that is one rank's alone ends the whole job, since the others would wait for that rank.
  const MpiRank job = launched_rank();
  init_logging(false, args.quiet || job.rank != 0);
  if (job.rank != 0) spdlog::set_level(spdlog::level::err);
  const auto fail = [&](const Error& e, int status) {
    if (job.size > 1 && !dynamic_cast<const JobError*>(&e)) {
      std::cerr << "rift: rank " << job.rank << " of " << job.size << ": " << e.what()
                << "\nrift: ending every rank of the job\n";
      std::cerr.flush();
      MPI_Abort(MPI_COMM_WORLD, status);
    }
    if (job.rank == 0) spdlog::error("{}", e.what());
    return status;
  };
  std::optional<Scene> scene;
  {
    // The scene's errors are the same on every rank: rank 0 prints them.
    std::ostringstream quiet;
    std::streambuf* err = job.rank != 0 ? std::cerr.rdbuf(quiet.rdbuf()) : nullptr;
    scene = read_scene(args.scene);
    if (err) std::cerr.rdbuf(err);
  }
  if (!scene) return 2;
  RunOptions options;
  options.out_dir = args.out_dir.empty() ? std::filesystem::path("rift-out") / safe_folder_name(scene->name)
                                         : std::filesystem::path(args.out_dir);
  options.threads = args.threads;
  options.restart_latest = args.restart == "latest";
  options.overwrite = args.overwrite;
  options.progress = !args.quiet;
  if (args.stop_after) options.stop_after_step = *args.stop_after;
  if (!args.restart.empty() && args.restart != "latest") {
    std::cerr << "--restart: expected 'latest', found '" << args.restart << "'\n";
    return 2;
  }
  std::unique_ptr<RunLoop> sim;
  try {
    sim = std::make_unique<RunLoop>(std::move(*scene), options, build);
  } catch (const Error& e) {
    return fail(e, 2);
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    const RunResult r = sim->run();
    if (job.rank != 0) return r.stop_reason == "signal" ? 130 : 0;
    std::cout << "output: " << options.out_dir.string() << "/: " << grid_files(options.out_dir)
              << "(open in ParaView; rift.xdmf holds every grid), summary.json, timeseries.csv\n";
    print_run_report(options.out_dir);
    if (r.completed)
      for (const auto& m : read_reference_metrics(sim->scene().reference, options.out_dir)) {
        if (!m.value)
          std::cout << "reference " << m.name << ": " << m.problem << "\n";
        else if (m.reference)
          std::printf("reference %s = %.9g (analytic %.9g, relative error %.3g)\n", m.name.c_str(), *m.value,
                      *m.reference, relative_error(*m.value, *m.reference));
        else
          std::printf("reference %s = %.9g\n", m.name.c_str(), *m.value);
      }
    return r.stop_reason == "signal" ? 130 : 0;
  } catch (const Error& e) {
    return fail(e, 1);
  }
}

int plot(const std::string& run_dir, const std::string& out_dir) {
  const RunPlotResult r = plot_run(run_dir, out_dir);
  if (!r.problem.empty()) {
    std::cerr << "rift plot: " << r.problem << "\n";
    return 2;
  }
  for (const auto& p : r.pictures) std::cout << p.string() << "\n";
  return 0;
}

int render(const std::string& run_dir, const RenderOptions& options) {
  const RenderResult r = render_run(run_dir, options);
  for (const auto& p : r.pictures) std::cout << p.string() << "\n";
  if (!r.problem.empty()) {
    std::cerr << "rift render: " << r.problem << "\n";
    return 2;
  }
  return 0;
}

int schema(const std::string& out_file) {
  const SceneSchema s = scene_schema();
  // The built-in docs' examples are read at every build's test; a problem here is a defect of Rift.
  if (!s.problems.empty()) {
    for (const auto& p : s.problems) std::cerr << p << "\n";
    std::cerr << "rift schema: the built-in complete examples do not read; no schema written\n";
    return 1;
  }
  if (out_file.empty()) {
    std::cout << s.json;
    return 0;
  }
  try {
    write_text_atomic(out_file, s.json);
  } catch (const Error& e) {
    std::cerr << "rift schema: " << e.what() << "\n";
    return 2;
  }
  std::cout << out_file << ": JSON Schema (draft-07) of the scene format, " << s.keys << " keys\n";
  return 0;
}

int sweep(const SweepArgs& args, const WorldBuilder& build) {
  init_logging(false, true);
  if (args.scene.scene.empty()) {
    std::cerr << "rift sweep: give a scene file\n";
    return 2;
  }
  SweepOptions o;
  o.scene_path = args.scene.scene;
  o.overrides = args.scene.overrides;
  o.threads = args.threads;
  o.build_world = build;
  try {
    for (const auto& v : args.vary) o.axes.push_back(parse_sweep_axis(v));
    o.out_dir = args.out_dir.empty() ? std::filesystem::path("rift-out") /
                                           safe_folder_name("sweep-" + load_scene(o.scene_path).name)
                                     : std::filesystem::path(args.out_dir);
  } catch (const Error& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    const SweepResult r = run_sweep(o);
    std::cout << "sweep: " << r.rows.size() << " variants in " << (o.out_dir / "sweep.csv").string() << " ("
              << r.ran << " run now)\n";
    if (!r.plot_note.empty()) std::cout << r.plot_note << "\n";
    if (r.interrupted) {
      std::cout << "interrupted: run the same command again to finish the sweep\n";
      return 130;
    }
    return 0;
  } catch (const Error& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
}

int check(const SceneArgs& args, const WorldBuilder& build) {
  init_logging(false, true);
  auto scene = read_scene(args);
  if (!scene) return 2;
  // What depends on the mesh (surface and region names, element quality, the stable step, a fluid mesh
  // that must fit the solid) is checked by the set-up itself, as `rift run` does it, without stepping
  // or writing anything.
  spdlog::info("the scene reads; building its mesh and models to check what depends on them");
  const std::string resolved = scene->resolved_yaml, hash = scene->hash;
  try {
    RunOptions options;
    options.write_output = false;
    options.progress = false;
    RunLoop set_up(std::move(*scene), options, build);
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  std::cout << "# " << (args.scene.empty() ? default_scene_name : args.scene)
            << ": valid (scene, mesh and set-up); resolved scene, hash " << hash << "\n"
            << resolved << "\n";
  return 0;
}

int info() {
  std::cout << "Rift " << build::version << "\n"
            << "build: " << build::build_type << ", " << build::compiler
            << ", native ISA: " << (build::native ? "yes" : "no")
            << ", sanitizers: " << (build::sanitized ? "yes" : "no") << "\n"
            << "flags: " << build::cxx_flags << "\n";
  unsigned h5maj, h5min, h5rel;
  H5get_libversion(&h5maj, &h5min, &h5rel);
  std::printf("libraries:\n");
  std::printf("  Eigen       %d.%d.%d\n", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION);
  std::printf("  oneTBB      %s (runtime interface %d)\n", TBB_VERSION_STRING,
              TBB_runtime_interface_version());
  std::printf("  HDF5        %u.%u.%u\n", h5maj, h5min, h5rel);
  std::printf("  METIS       %d.%d.%d\n", METIS_VER_MAJOR, METIS_VER_MINOR, METIS_VER_SUBMINOR);
  std::printf("  CGAL        %s\n", CGAL_VERSION_STR);
  std::printf("  yaml-cpp    %s\n", RIFT_YAML_CPP_VERSION);
  std::printf("  nlohmann    %d.%d.%d\n", NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
              NLOHMANN_JSON_VERSION_PATCH);
  std::printf("  spdlog      %d.%d.%d\n", SPDLOG_VER_MAJOR, SPDLOG_VER_MINOR, SPDLOG_VER_PATCH);
  std::printf("  fmt         %d.%d.%d\n", FMT_VERSION / 10000, FMT_VERSION / 100 % 100, FMT_VERSION % 100);
  std::printf("  CLI11       %s\n", CLI11_VERSION);
  std::printf("  hypre       %s\n", HYPRE_RELEASE_VERSION);
#if defined(OMPI_MAJOR_VERSION)
  std::printf("  MPI         Open MPI %d.%d.%d (MPI %d.%d; serial runs use singleton mode)\n",
              OMPI_MAJOR_VERSION, OMPI_MINOR_VERSION, OMPI_RELEASE_VERSION, MPI_VERSION, MPI_SUBVERSION);
#else
  std::printf("  MPI         %d.%d\n", MPI_VERSION, MPI_SUBVERSION);
#endif
  return 0;
}

int graph(const SceneArgs& args, int threads, const WorldBuilder& build) {
  init_logging(false, true);
  auto scene = read_scene(args);
  if (!scene) return 2;
  try {
    RunOptions options;
    options.write_output = false;
    options.progress = false;
    options.threads = threads;
    RunLoop sim(std::move(*scene), options, build);
    // The script the graph comes from, as a DOT comment: the order of stages, the windows, and the work
    // beside and after the graph, which has no box in it.
    std::cout << "/* the step, as the composition root scripts it:\n"
              << sim.world().plan.script() << "\n*/\n"
              << sim.graph().dot();
  } catch (const Error& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}

int partition(const PartitionArgs& args, const WorldBuilder& build) {
  init_logging(false, true);
  auto scene = read_scene(args.scene);
  if (!scene) return 2;
  if (args.latency_us < 0.0 || args.bandwidth_gbs <= 0.0) {
    std::cerr << "rift partition: --latency must be at least 0 and --bandwidth above 0\n";
    return 2;
  }
  try {
    RunOptions options;
    options.write_output = false;
    options.progress = false;
    RunLoop set_up(std::move(*scene), options, build);
    const std::vector<PartitionWork> domains = collect_partition_work(set_up.world());
    NetworkModel network;
    network.latency = args.latency_us * 1e-6;
    network.bandwidth = args.bandwidth_gbs * 1e9;
    nlohmann::json j = {{"scene", args.scene.scene},
                        {"network",
                         {{"latency_s", network.latency},
                          {"bandwidth_Bps", network.bandwidth},
                          {"unit_seconds", network.unit_seconds}}}};
    std::string text;
    for (const PartitionWork& work : domains) {
      std::vector<PartitionReport> reports;
      for (int ranks : args.ranks) {
        if (ranks < 1 || size_t(ranks) > work.graph_tets.size())
          throw Error(fmt::format("rift partition: --ranks {}: give 1 to the {} mesh's {} tets", ranks,
                                  work.domain, work.graph_tets.size()));
        reports.push_back(report_partition(work, ranks, network));
      }
      text += fmt::format("# {} of {}: {} tets, {} nodes, {} B a ghost node an exchange", work.domain,
                          args.scene.scene.empty() ? default_scene_name : args.scene.scene,
                          work.graph_tets.size(), work.nodes, work.node_bytes);
      text += work.timed ? fmt::format(
                               "; work units of {:.0f} ns a step; network: {} us a message, {} GB/s a "
                               "rank\n",
                               network.unit_seconds * 1e9, args.latency_us, args.bandwidth_gbs)
                         : "; no time predicted (the exchanges per step depend on the solver's iterations)\n";
      text += partition_table(reports);
      nlohmann::json d = {{"domain", work.domain},
                          {"tets", work.graph_tets.size()},
                          {"nodes", work.nodes},
                          {"node_bytes", work.node_bytes},
                          {"timed", work.timed}};
      for (const PartitionReport& r : reports) d["partitions"].push_back(to_json(r));
      j["domains"].push_back(d);
    }
    std::cout << text;
    if (!args.json_out.empty()) write_text_atomic(args.json_out, j.dump(2) + "\n");
  } catch (const Error& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}

}  // namespace rift::cli
