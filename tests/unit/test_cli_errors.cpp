// The rift binary on input and folders it cannot use: a message naming what and where, exit 2 (bad input,
// nothing written) or 1, never an abort on an exception.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/unit/test_cli_support.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

// The built-in quickstart scene, a few steps of it.
std::vector<std::string> quick_run(const fs::path& out, std::vector<std::string> more = {}) {
  std::vector<std::string> args{"run", "--out", out.string(), "--set", "time.end=2.0e-6", "--quiet"};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// A traction of 1e300 Pa overflows the energies in the first steps: the run stops naming the quantity,
// and neither the time series nor the summary holds inf, nan or null.
TEST(Cli, ANonFiniteQuantityStopsTheRunAndReachesNoFile) {
  test::TempDir dir;
  const CliResult r = rift(quick_run(dir / "out", {"--set", "solid.boundaries[1].value=1e300"}));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("is not finite, so the output was not written"), std::string::npos) << r.output;
  auto text = [](const fs::path& f) {
    std::ifstream in(f);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string csv = text(dir / "out" / "timeseries.csv");
  const std::string summary = text(dir / "out" / "summary.json");
  ASSERT_FALSE(csv.empty());
  ASSERT_FALSE(summary.empty());
  for (const char* bad : {"inf", "nan"}) EXPECT_EQ(csv.find(bad), std::string::npos) << csv;
  EXPECT_EQ(summary.find("null"), std::string::npos) << summary;
}

// rift check builds the mesh and the models as a run's set-up does, so what depends on the mesh (here a
// misspelt surface name) is caught before any run, with a suggestion; a good scene still checks.
TEST(Cli, CheckCatchesWhatTheSetUpWouldRefuse) {
  const std::string cavity = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/cavity.yaml";
  const CliResult bad = rift({"check", cavity, "--set", "fluid.boundaries[1].surface=xmn"});
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(
      bad.output.find("fluid.boundaries[1].surface: the mesh has no surface 'xmn' (did you mean 'xmin'?)"),
      std::string::npos)
      << bad.output;
  const CliResult good = rift({"check", cavity});
  EXPECT_EQ(good.exit_code, 0) << good.output;
  EXPECT_NE(good.output.find("valid (scene, mesh and set-up)"), std::string::npos) << good.output;
}

// A finished run is extended by restarting with a later time.end (and output settings): it continues from
// its last checkpoint with the steps it took, to the new end. Any other change is refused, naming the keys.
TEST(Cli, AFinishedRunIsExtendedByALaterEndTime) {
  test::TempDir dir;
  const fs::path out = dir / "out";
  const std::string scene = std::string(RIFT_SOURCE_DIR) + "/scenes/validation/single_joint_mode_I.yaml";
  const std::vector<std::string> base{"run",        scene,   "--out",
                                      out.string(), "--set", "checkpoint.every_steps=1000"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  const CliResult first = rift(with({"--set", "time.end=1.0e-3"}));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const CliResult changed = rift(
      with({"--set", "time.end=2.0e-3", "--set", "solid.materials[0].density=3000", "--restart", "latest"}));
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("they differ in solid.materials[0].density, time.end"), std::string::npos)
      << changed.output;
  const CliResult extended =
      rift(with({"--set", "time.end=2.0e-3", "--set", "output.interval=5.0e-4", "--restart", "latest"}));
  ASSERT_EQ(extended.exit_code, 0) << extended.output;
  EXPECT_NE(extended.output.find("extending the run to t = 0.002 s"), std::string::npos) << extended.output;
  std::ifstream summary(out / "summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), {});
  EXPECT_NE(text.find("\"status\": \"completed\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"simulated_time\": 0.002"), std::string::npos) << text;
}

// A second run into a folder that holds a run is refused (its files would mix with the earlier run's);
// --overwrite deletes the earlier run's files first, and leaves a user's own file alone.
TEST(Cli, AnEarlierRunInTheFolderIsRefusedUnlessOverwritten) {
  test::TempDir dir;
  const fs::path out = dir / "out";
  const CliResult first =
      rift(quick_run(out, {"--set", "time.end=4.0e-6", "--set", "output.interval=1.0e-6"}));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::ofstream(out / "notes.txt") << "mine";
  size_t outputs_before = 0;
  for (const auto& e : fs::directory_iterator(out)) outputs_before += e.path().extension() == ".h5";
  const CliResult again = rift(quick_run(out));
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find("holds an earlier run"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("--overwrite"), std::string::npos) << again.output;
  const CliResult replaced = rift(quick_run(out, {"--overwrite"}));
  ASSERT_EQ(replaced.exit_code, 0) << replaced.output;
  size_t outputs_after = 0;
  for (const auto& e : fs::directory_iterator(out)) outputs_after += e.path().extension() == ".h5";
  EXPECT_LT(outputs_after, outputs_before) << "the longer run's later outputs were left behind";
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
}

TEST(Cli, SetIndexOutOfRangeIsBadInput) {
  test::TempDir dir;
  const std::string set = "solid.materials[99999999999999999999].density=1";
  const CliResult r = rift(quick_run(dir / "out", {"--set", set}));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--set " + set +
                          ": solid.materials[99999999999999999999]: expected a list index, "
                          "found index 99999999999999999999, which is out of range"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Sizes that ask for billions of tets are refused in a second, before meshing and before any file.
TEST(Cli, AMeshBeyondTheElementBudgetIsBadInput) {
  test::TempDir dir;
  const CliResult r = rift(quick_run(
      dir / "out", {"--set", "mesh.generate.size_min=3e-5", "--set", "mesh.generate.size_max=3e-5"}));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("the sizes ask for about 7.05e+09 tets"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("raise mesh.max_elements"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// A device named as the scene is refused at once (read whole, /dev/zero would exhaust memory).
TEST(Cli, ADeviceAsTheSceneIsBadInput) {
  test::TempDir dir;
  const CliResult r = rift({"run", "/dev/zero", "--out", (dir / "out").string(), "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(
      r.output.find("/dev/zero: expected a readable scene file, found the scene file is not a regular file"),
      std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Cli, OutputFolderThatIsARegularFileIsRefused) {
  test::TempDir dir;
  const fs::path file = dir / "somefile";
  std::ofstream(file) << "not a folder";
  const CliResult r = rift(quick_run(file));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("output folder '" + file.string() +
                          "' exists and is not a folder (it is a regular file)"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(test::slurp(file), "not a folder");

  const CliResult under = rift(quick_run(file / "x"));
  EXPECT_EQ(under.exit_code, 2) << under.output;
  EXPECT_NE(under.output.find("cannot create output folder '" + (file / "x").string() + "': Not a directory"),
            std::string::npos)
      << under.output;
}

TEST(Cli, SweepOutputFolderThatIsARegularFileIsRefused) {
  test::TempDir dir;
  const fs::path file = dir / "somefile";
  std::ofstream(file) << "not a folder";
  const CliResult r = rift({"sweep", std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml",
                            "--vary", "time.end=2.0e-6,4.0e-6", "--out", file.string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("output folder '" + file.string() + "' exists and is not a folder"),
            std::string::npos)
      << r.output;
}

TEST(Cli, OutputFolderTheSystemRefusesIsReported) {
  const CliResult r = rift(quick_run("/proc/rift-x"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot create output folder '/proc/rift-x': "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
}

TEST(Cli, UnwritableOutputFolderIsReported) {
  if (::geteuid() == 0)
    GTEST_SKIP()
        << "running as root: permission bits do not stop root's writes, so a 0555 folder is writable";
  test::TempDir dir;
  const fs::path locked = dir / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  const CliResult r = rift(quick_run(locked));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot write into output folder '" + locked.string() + "': Permission denied"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::is_empty(locked));
  const CliResult below = rift(quick_run(locked / "run"));
  EXPECT_EQ(below.exit_code, 2) << below.output;
  EXPECT_NE(
      below.output.find("cannot create output folder '" + (locked / "run").string() + "': Permission denied"),
      std::string::npos)
      << below.output;
  fs::permissions(locked, fs::perms::owner_all);
}

TEST(Cli, LogFileThatCannotBeOpenedIsReported) {
  test::TempDir dir;
  fs::create_directories(dir / "out" / "rift.log");  // a folder where the log file goes
  const CliResult r = rift(quick_run(dir / "out"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(
      r.output.find("cannot open the log file '" + (dir / "out" / "rift.log").string() + "': Is a directory"),
      std::string::npos)
      << r.output;
}

TEST(Cli, ALinkAtTheLogFileIsRefusedNotWrittenThrough) {
  test::TempDir dir;
  std::ofstream(dir / "victim") << "precious";
  fs::create_directories(dir / "out");
  fs::create_symlink(dir / "victim", dir / "out" / "rift.log");
  const CliResult r = rift(quick_run(dir / "out"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot open the log file '" + (dir / "out" / "rift.log").string() +
                          "': it is a symbolic link, which Rift does not write through"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(test::slurp(dir / "victim"), "precious");
}

TEST(Cli, ACheckpointsLinkOutOfTheOutputFolderIsRefused) {
  test::TempDir dir;
  fs::create_directories(dir / "elsewhere");
  std::ofstream(dir / "elsewhere" / "ckpt_0000000001.h5") << "precious";
  fs::create_directories(dir / "out");
  fs::create_directory_symlink(dir / "elsewhere", dir / "out" / "checkpoints");
  const CliResult r =
      rift(quick_run(dir / "out", {"--set", "checkpoint.every_steps=1", "--set", "checkpoint.keep=1"}));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'" + (dir / "out" / "checkpoints").string() + "' is a symbolic link"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(test::slurp(dir / "elsewhere" / "ckpt_0000000001.h5"), "precious");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "elsewhere"), {}), 1);
}

TEST(Cli, RestartFromADamagedTimeSeriesIsRefused) {
  test::TempDir dir;
  const fs::path out = dir / "out";
  const CliResult first = rift(quick_run(out, {"--stop-after", "5"}));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::vector<std::string> lines;
  {
    std::ifstream in(out / "timeseries.csv");
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  ASSERT_GT(lines.size(), 3u);
  lines[2] = "1,1e999999" + lines[2].substr(lines[2].find(',', 2));  // line 3: step 1, time out of range
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  std::ofstream(out / "timeseries.csv") << text;
  const CliResult r = rift(quick_run(out, {"--restart", "latest"}));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find((out / "timeseries.csv").string() +
                          ":3: field 2 (time): expected a number, found '1e999999', which is out of range"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(test::slurp(out / "timeseries.csv"), text);
}

TEST(Cli, RestartWithNoIntactCheckpointIsBadInputNamingThem) {
  test::TempDir dir;
  const fs::path out = dir / "out";
  const CliResult first = rift(quick_run(out, {"--stop-after", "5", "--set", "checkpoint.every_steps=2"}));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::vector<fs::path> checkpoints;
  for (const auto& e : fs::directory_iterator(out / "checkpoints")) checkpoints.push_back(e.path());
  ASSERT_EQ(checkpoints.size(), 2u);
  for (const auto& c : checkpoints) fs::resize_file(c, fs::file_size(c) / 2);
  const CliResult r = rift(quick_run(out, {"--restart", "latest", "--set", "checkpoint.every_steps=2"}));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--restart latest: no intact checkpoint in " + (out / "checkpoints").string()),
            std::string::npos)
      << r.output;
  for (const auto& c : checkpoints)
    EXPECT_NE(r.output.find("  " + c.string() + ": "), std::string::npos) << r.output;
}

// A killed run's temp files are deleted by the next run in the folder, when they are named after one
// of its outputs and their writer is gone; a link, another name and a live writer's file stay.
TEST(Cli, AKilledRunsTempFilesAreRemovedAndOnlyThose) {
  test::TempDir dir;
  const fs::path out = dir / "out";
  fs::create_directories(out);
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);  // a pid that no longer runs
  const std::string dead = std::to_string(child), live = std::to_string(::getpid());
  const std::vector<std::string> orphans{"timeseries.csv.tmp-" + dead, "rift.xdmf.tmp-" + dead,
                                         "rift_00000010.h5.tmp-" + dead, "summary.json.tmp-" + dead};
  const std::vector<std::string> kept{"notes.txt.tmp-" + dead, "timeseries.csv.tmp-" + live,
                                      "rift.xdmf.tmp-0" + dead, "scene.yaml.tmp-" + dead};
  for (const auto& name : orphans) std::ofstream(out / name) << "torn";
  for (const auto& name : kept) std::ofstream(out / name) << "not a killed run's";
  std::ofstream(dir / "target") << "the link's target";
  fs::remove(out / ("scene.yaml.tmp-" + dead));
  fs::create_symlink(dir / "target", out / ("scene.yaml.tmp-" + dead));
  const CliResult r = rift(quick_run(out));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const auto& name : orphans) EXPECT_FALSE(fs::exists(out / name)) << name;
  for (const auto& name : kept) EXPECT_TRUE(fs::is_symlink(out / name) || fs::exists(out / name)) << name;
  EXPECT_EQ(test::slurp(dir / "target"), "the link's target");
  EXPECT_NE(r.output.find("removed 4 temporary file(s) a killed run left"), std::string::npos) << r.output;
}

TEST(Cli, StrayCheckpointTempFilesAreLeftAlone) {
  test::TempDir dir;
  const fs::path out = dir / "out";
  fs::create_directories(out / "checkpoints");
  const std::vector<std::string> stray{"ckpt_000100.h5.tmp-99999999999999999999",
                                       "ckpt_0000000100.h5.tmp-99999999999999999999"};
  for (const auto& name : stray) std::ofstream(out / "checkpoints" / name) << "not ours";
  const CliResult r = rift(quick_run(out, {"--set", "checkpoint.every_steps=5"}));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const auto& name : stray) EXPECT_TRUE(fs::exists(out / "checkpoints" / name)) << name;
  int written = 0;
  for (const auto& e : fs::directory_iterator(out / "checkpoints")) written += e.path().extension() == ".h5";
  EXPECT_GT(written, 0) << "the run wrote no checkpoint";
}

}  // namespace
}  // namespace rift
