// A whole run through the same path as `rift run`: restart continues bit-for-bit, and the state is
// identical on 1, 2 and 4 threads.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "engine/core/state_hash.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"
#include "tests/unit/test_checkpoint_damage.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

using namespace rift;
namespace fs = std::filesystem;

namespace {

Scene small_scene() {
  // The quickstart scene, shortened: 60 steps are enough to spread the wave through the bar.
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  return load_scene(path, {"time.end=2.0e-5", "output.interval=4.0e-6"});
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rift_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

using test::run_scene;

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields(1);
  for (char c : line)
    if (c == ',')
      fields.emplace_back();
    else
      fields.back() += c;
  return fields;
}

std::string joined(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
  return line;
}

// Every file under `dir` with its bytes.
std::map<fs::path, std::string> files_in(const fs::path& dir) {
  std::map<fs::path, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[e.path()] = test::slurp(e.path());
  return files;
}

}  // namespace

TEST(Run, RestartIsBitwiseIdenticalToAStraightRun) {
  const Scene scene = small_scene();
  const fs::path a = fresh_dir("straight"), b = fresh_dir("restarted");
  const RunResult straight = run_scene(scene, a, 1);
  ASSERT_TRUE(straight.completed);
  ASSERT_GT(straight.steps, 10);
  const int64_t half = straight.steps / 2;
  const RunResult first = run_scene(scene, b, 1, half);
  EXPECT_FALSE(first.completed);
  EXPECT_EQ(first.steps, half);
  EXPECT_TRUE(fs::exists(b / "checkpoints"));
  const RunResult second = run_scene(scene, b, 1, std::nullopt, true);
  EXPECT_TRUE(second.completed);
  EXPECT_EQ(second.steps, straight.steps);
  EXPECT_EQ(hex64(second.state_hash), hex64(straight.state_hash));
  // The restarted run's outputs continue the series: same summary figures, same time-series rows.
  std::ifstream ta(a / "timeseries.csv"), tb(b / "timeseries.csv");
  std::string sa((std::istreambuf_iterator<char>(ta)), {}), sb((std::istreambuf_iterator<char>(tb)), {});
  EXPECT_EQ(sa, sb);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Run, RestartAfterAFractureIsBitwiseIdentical) {
  // One joint opened to failure (breaks near step 19,000 of 24,580): the restart point lies after the
  // break, so the damage history, the broken flag and the fracture log all go through the checkpoint.
  const Scene scene =
      load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/single_joint_mode_I.yaml", {});
  const fs::path a = fresh_dir("frac_straight"), b = fresh_dir("frac_restarted");
  const RunResult straight = run_scene(scene, a, 1);
  ASSERT_TRUE(straight.completed);
  run_scene(scene, b, 2, straight.steps - 2000);
  const RunResult second = run_scene(scene, b, 1, std::nullopt, true);
  EXPECT_EQ(hex64(second.state_hash), hex64(straight.state_hash));
  std::ifstream fa(a / "fractures.csv"), fb(b / "fractures.csv");
  std::string sa((std::istreambuf_iterator<char>(fa)), {}), sb((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_EQ(sa, sb);
  EXPECT_NE(sa.find("tensile"), std::string::npos) << sa;
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Run, RestartRefusesADamagedTimeSeriesAndLeavesTheFolderAlone) {
  // The restart carries timeseries.csv's rows on, so a field that is no number, one beyond a double's
  // range, or a row cut short is reported with the file, line and field, before any file changes.
  const Scene scene = small_scene();
  const fs::path dir = fresh_dir("damaged_series");
  run_scene(scene, dir, 1, 10);
  const fs::path csv = dir / "timeseries.csv";
  std::vector<std::string> lines;
  {
    std::ifstream in(csv);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  ASSERT_GT(lines.size(), 6u);
  const std::vector<std::string> header = fields_of(lines[0]), row = fields_of(lines[5]);  // line 6
  ASSERT_EQ(row.size(), header.size());
  std::vector<std::string> abc = row, huge = row, cut = row;
  abc[1] = "abc";
  huge[2] = "1e999999";
  cut.pop_back();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {abc, ":6: field 2 (time): expected a number, found 'abc'"},
      {huge, ":6: field 3 (" + header[2] +
                 "): expected a number, found '1e999999', which is out of range of a double"},
      {cut, ":6: expected " + std::to_string(header.size()) + " fields as in the header, found " +
                std::to_string(cut.size())},
  };
  for (const auto& [damaged, message] : cases) {
    lines[5] = joined(damaged);
    std::string text;
    for (const auto& l : lines) text += l + "\n";
    std::ofstream(csv) << text;
    const auto before = files_in(dir);
    RunOptions o;
    o.out_dir = dir;
    o.progress = false;
    o.restart_latest = true;
    const std::string m = test::error_of([&] { Simulation(scene, o); });
    EXPECT_NE(m.find("--restart latest: " + csv.string() + message), std::string::npos) << m;
    EXPECT_TRUE(files_in(dir) == before) << "the refused restart changed " << dir;
  }
  fs::remove_all(dir);
}

TEST(Run, RestartFallsBackPastADamagedCheckpointAndRefusesWhenNoneIsIntact) {
  // One changed byte in the newest checkpoint's values: the restart says which file and why, continues
  // from the previous checkpoint and still ends bit for bit where a straight run ends.
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  const Scene scene =
      load_scene(path, {"time.end=2.0e-5", "output.interval=4.0e-6", "checkpoint.every_steps=4"});
  const fs::path a = fresh_dir("fallback_straight"), b = fresh_dir("fallback_restarted");
  const RunResult straight = run_scene(scene, a, 1);
  ASSERT_TRUE(straight.completed);
  run_scene(scene, b, 1, 10);
  const fs::path newest = b / "checkpoints" / "ckpt_0000000010.h5";
  const fs::path previous = b / "checkpoints" / "ckpt_0000000008.h5";
  ASSERT_TRUE(fs::exists(newest));
  ASSERT_TRUE(fs::exists(previous));
  const std::string column = test::contiguous_column(newest);
  test::flip_dataset_byte(newest, column, 3);

  const RunResult resumed = run_scene(scene, b, 1, std::nullopt, true);
  EXPECT_TRUE(resumed.completed);
  EXPECT_EQ(hex64(resumed.state_hash), hex64(straight.state_hash));
  const std::string log = test::slurp(b / "rift.log");
  EXPECT_NE(log.find("[warning] --restart latest: skipping " + newest.string() + ": checkpoint " +
                     newest.string() + " is damaged: its bytes do not match its seal"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("restarted from " + previous.string() + " at step 8"), std::string::npos) << log;

  // Every checkpoint damaged: refused, each named with its reason, the folder left as it was.
  const fs::path c = fresh_dir("fallback_none");
  run_scene(scene, c, 1, 10);
  const fs::path c_newest = c / "checkpoints" / "ckpt_0000000010.h5";
  const fs::path c_previous = c / "checkpoints" / "ckpt_0000000008.h5";
  test::flip_dataset_byte(c_newest, test::contiguous_column(c_newest), 0);
  std::ofstream(c_previous, std::ios::binary | std::ios::trunc) << "cut";
  const auto before = files_in(c);
  RunOptions o;
  o.out_dir = c;
  o.progress = false;
  o.restart_latest = true;
  const std::string m = test::error_of([&] { Simulation(scene, o); });
  EXPECT_NE(m.find("--restart latest: no intact checkpoint in " + (c / "checkpoints").string()),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("\n  " + c_newest.string() + ": checkpoint " + c_newest.string() + " is damaged"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("\n  " + c_previous.string() + ": checkpoint " + c_previous.string() +
                   " is damaged: it does not start with its seal"),
            std::string::npos)
      << m;
  EXPECT_TRUE(files_in(c) == before) << "the refused restart changed " << c;
  fs::remove_all(a);
  fs::remove_all(b);
  fs::remove_all(c);
}

TEST(Run, RestartRefusesAMeshFileReplacedAtTheSamePath) {
  // The scene hash covers the mesh file's bytes: a restart on another mesh under the same name is another
  // scene, refused like a changed key, and the folder stays as it was.
  const fs::path dir = fresh_dir("replaced_mesh");
  fs::create_directories(dir / "in");
  const std::string source = std::string(RIFT_SOURCE_DIR) + "/scenes/validation/";
  fs::copy_file(source + "single_joint_mode_I.yaml", dir / "in" / "scene.yaml");
  fs::copy_file(source + "two_tets.msh", dir / "in" / "two_tets.msh");
  const std::vector<std::string> shorter{"time.end=2.0e-5"};
  const fs::path out = dir / "out";
  run_scene(load_scene((dir / "in" / "scene.yaml").string(), shorter), out, 1, 20);
  const std::string original = test::slurp(dir / "in" / "two_tets.msh");
  std::ofstream(dir / "in" / "two_tets.msh", std::ios::binary)
      << original << "$Comments\nreplaced\n$EndComments\n";
  const Scene replaced = load_scene((dir / "in" / "scene.yaml").string(), shorter);
  const auto before = files_in(out);
  RunOptions o;
  o.out_dir = out;
  o.progress = false;
  o.restart_latest = true;
  const std::string m = test::error_of([&] { Simulation(replaced, o); });
  EXPECT_NE(m.find("was written for scene hash"), std::string::npos) << m;
  EXPECT_NE(m.find("this scene resolves to " + replaced.hash), std::string::npos) << m;
  EXPECT_TRUE(files_in(out) == before) << "the refused restart changed " << out;

  // Changed between reading the scene and building the world: the mesh is not built from other bytes
  // than the hash says.
  o.out_dir = dir / "other";
  o.restart_latest = false;
  std::ofstream(dir / "in" / "two_tets.msh", std::ios::binary) << original;
  EXPECT_NE(
      test::error_of([&] { Simulation(replaced, o); }).find("the mesh file changed after the scene was read"),
      std::string::npos);

  const RunResult resumed =
      run_scene(load_scene((dir / "in" / "scene.yaml").string(), shorter), out, 1, {}, true);
  EXPECT_TRUE(resumed.completed);
  fs::remove_all(dir);
}

TEST(Run, FractureZoneMaterialWithoutFracturePropertiesIsRefused) {
  Scene scene = load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/patch_uniaxial.yaml", {});
  scene.solid->materials[0].fracture.reset();
  RunOptions o;
  o.write_output = false;
  try {
    Simulation sim(scene, o);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("solid.materials[0] ('limestone') fills tets of the fracture zone"), std::string::npos)
        << m;
    EXPECT_NE(m.find("tensile_strength"), std::string::npos) << m;
  }
}

TEST(Run, NodeSetInABoxHoldsTheSameNodesAsTheSurface) {
  // The quickstart bar is clamped on surface xmin (x = 0); a node set of the box |x| <= 1e-9 m holds
  // exactly those nodes, so the run must end in the same state.
  const Scene by_surface = small_scene();
  Scene by_box = small_scene();
  SolidBoundarySpec& clamp = by_box.solid->boundaries[0];
  ASSERT_EQ(clamp.surface, "xmin");
  clamp.surface.clear();
  clamp.box_min = std::array<double, 3>{-1e-9, -1, -1};
  clamp.box_max = std::array<double, 3>{1e-9, 1, 1};
  const fs::path a = fresh_dir("surface_clamp"), b = fresh_dir("box_clamp");
  EXPECT_EQ(hex64(run_scene(by_surface, a, 1).state_hash), hex64(run_scene(by_box, b, 1).state_hash));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Run, NoFractureSectionMeansNoJoints) {
  // Model only what the scene requires: the quickstart bar has no fracture section, so its tets share
  // nodes and the run has no joint table and no joint system.
  RunOptions o;
  o.write_output = false;
  Simulation sim(small_scene(), o);
  EXPECT_FALSE(sim.world().store.has("solid_joint"));
  for (System* s : sim.world().systems()) EXPECT_NE(s->name(), "joint_forces");
}

TEST(Run, SameStateOnOneTwoAndFourThreads) {
  const Scene scene = small_scene();
  std::string reference;
  for (int threads : {1, 2, 4}) {
    const fs::path dir = fresh_dir("threads" + std::to_string(threads));
    const RunResult r = run_scene(scene, dir, threads);
    if (threads == 1) reference = hex64(r.state_hash);
    EXPECT_EQ(hex64(r.state_hash), reference) << threads << " threads";
    fs::remove_all(dir);
  }
}

// 1e-25 s steps to the quickstart's end are more than a double counts exactly, and beyond int64: the
// count once came back as one step of time.end, and the run said `completed`.
TEST(Run, RefusesAStepCountNoRunCanFinish) {
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  for (const char* dt : {"time.dt=1.0e-25", "time.dt=1.0e-300"}) {
    const Scene scene = load_scene(path, {dt});
    RunOptions o;
    o.write_output = false;
    try {
      Simulation sim(scene, o);
      FAIL() << "expected a refusal for " << dt;
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("more than a run can count (2^53) or finish"), std::string::npos) << m;
      EXPECT_NE(m.find("(time.dt)"), std::string::npos) << m;
    }
  }
}

TEST(Run, RefusesADtAboveTheStableStep) {
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  const Scene scene = load_scene(path, {"time.dt=1.0e-5"});
  RunOptions o;
  o.write_output = false;
  try {
    Simulation sim(scene, o);
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("time.dt = 1e-05 s is above the stable step"), std::string::npos) << m;
    EXPECT_NE(m.find("allow_unstable_dt"), std::string::npos) << m;
  }
}

TEST(Run, InputErrorFoundWhileBuildingWritesNothing) {
  // The scene is valid YAML, but its boundary names a surface the generated box does not have: the run
  // must stop before the output folder exists, naming the key and the surfaces that do exist.
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  const Scene scene = load_scene(path, {"solid.boundaries[0].surface=top"});
  const fs::path dir = fresh_dir("bad_world");
  RunOptions o;
  o.out_dir = dir;
  o.progress = false;
  try {
    Simulation sim(scene, o);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("solid.boundaries[0].surface: the mesh has no surface 'top'"), std::string::npos) << m;
    EXPECT_NE(m.find("xmin"), std::string::npos) << m;
  }
  EXPECT_FALSE(fs::exists(dir));
}

TEST(Run, NoSolidSectionMeansNoSolidSystems) {
  // Model only what the scene requires: without a solid section the run has no solid tables or systems.
  const auto result = read_scene_text(
      "scene: {name: mesh-only}\ntime: {end: 1.0e-6, dt: 1.0e-7}\n"
      "mesh: {generate: {box: [0.02, 0.02, 0.02], size_min: 0.01, size_max: 0.01}}\n",
      "inline", ".");
  ASSERT_TRUE(result.scene) << result.errors.front().format();
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  Simulation sim(*result.scene, o);
  EXPECT_TRUE(sim.world().models.empty());
  EXPECT_TRUE(sim.world().systems().empty());
  EXPECT_FALSE(sim.world().store.has("solid_node"));
  const RunResult r = sim.run();
  EXPECT_TRUE(r.completed);
  EXPECT_EQ(r.steps, 10);
}
