// rift sweep on the single-joint scene (scenes/validation/single_joint_mode_I.yaml, whose reference
// section names the peak traction, f_t, and the dissipated energy, G_I): every variant runs, errors are
// computed against the analytic values (or the finest variant when a value is left out), the Pareto
// front is consistent, a second call resumes instead of rerunning, a sweep of another definition is
// refused, and a bad value stops the sweep before anything runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/spawn.hpp"
#include "engine/sweep/sweep.hpp"
#include "systems/world_builder.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

SweepOptions single_joint_sweep(const fs::path& out) {
  SweepOptions o;
  o.scene_path = std::string(RIFT_SOURCE_DIR) + "/scenes/validation/single_joint_mode_I.yaml";
  o.axes = {parse_sweep_axis("solid.fracture.integration_points=3,7")};
  o.out_dir = out;
  o.build_world = build_world;
  return o;
}

bool has_matplotlib() {
  return run_program({"python3", "-c", "import matplotlib"}) == 0 ||
         run_program({"/usr/bin/python3", "-c", "import matplotlib"}) == 0;
}

TEST(Sweep, RunsEveryVariantAndScoresItAgainstTheReference) {
  test::TempDir dir;
  const SweepResult r = run_sweep(single_joint_sweep(dir / "s"));
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_EQ(r.ran, 2u);
  EXPECT_EQ(r.metric_names, (std::vector<std::string>{"peak_traction", "fracture_energy"}));
  size_t on_front = 0;
  for (const auto& row : r.rows) {
    EXPECT_EQ(row.status, "done");
    EXPECT_GT(row.steps, 1000);
    EXPECT_EQ(row.tets, 2);
    ASSERT_TRUE(row.errors[0] && row.errors[1]);
    // The single-joint validation's bounds (docs/validation.md): peak within 1 %, energy within 2 %.
    EXPECT_LT(*row.errors[0], 0.01);
    EXPECT_LT(*row.errors[1], 0.02);
    EXPECT_DOUBLE_EQ(*row.error, std::max(*row.errors[0], *row.errors[1]));
    on_front += row.pareto;
  }
  EXPECT_GE(on_front, 1u);  // something is always on the front
  EXPECT_TRUE(fs::exists(dir / "s/sweep.csv"));
  EXPECT_TRUE(fs::exists(dir / "s/v000/summary.json"));
  EXPECT_TRUE(fs::exists(dir / "s/v001/summary.json"));
  const bool matplotlib = has_matplotlib();
  if (matplotlib) {
    EXPECT_TRUE(fs::exists(dir / "s/sweep.png")) << r.plot_note;
  }

  // Run again: nothing to do. Drop the last row (as an interruption would leave it): only that one reruns.
  EXPECT_EQ(run_sweep(single_joint_sweep(dir / "s")).ran, 0u);
  nlohmann::json state;
  std::ifstream(dir / "s/sweep.json") >> state;
  state["rows"].erase(1);
  std::ofstream(dir / "s/sweep.json") << state.dump();
  const SweepResult resumed = run_sweep(single_joint_sweep(dir / "s"));
  EXPECT_EQ(resumed.ran, 1u);
  EXPECT_EQ(resumed.rows.size(), 2u);

  // Another definition in the same folder is refused.
  SweepOptions other = single_joint_sweep(dir / "s");
  other.axes = {parse_sweep_axis("solid.materials[0].fracture.penalty=4e11,4e12")};
  EXPECT_THROW(run_sweep(other), Error);
}

TEST(Sweep, WithoutAnAnalyticValueTheFinestVariantIsTheReference) {
  test::TempDir dir;
  SweepOptions o = single_joint_sweep(dir / "s");
  o.axes = {parse_sweep_axis("solid.materials[0].fracture.penalty=4e11,4e12")};
  o.overrides = {"reference[0].value=null"};
  o.plot = false;
  const SweepResult r = run_sweep(o);
  ASSERT_EQ(r.rows.size(), 2u);
  ASSERT_GT(r.rows[1].steps, r.rows[0].steps);  // the stiffer joint takes the smaller step: the finest
  EXPECT_EQ(*r.rows[1].errors[0], 0.0);
  EXPECT_GT(*r.rows[0].errors[0], 0.0);
}

// The scene's name is the plot's title: a hostile name reaches the plotter as text and runs nothing.
TEST(Sweep, AHostileSceneNameRunsNoCommand) {
  test::TempDir dir;
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path());
  // --set values are YAML: a backtick may not start a plain scalar, so that one is double-quoted.
  for (const std::string name : {"x'; touch owned; echo '", "$(touch owned)", "\"`touch owned`\""}) {
    SweepOptions o = single_joint_sweep(dir / "s");
    o.axes = {parse_sweep_axis("solid.fracture.integration_points=3")};
    o.overrides = {"scene.name=" + name};
    const SweepResult r = run_sweep(o);
    EXPECT_EQ(r.rows.at(0).status, "done") << name;
    if (has_matplotlib()) {
      EXPECT_TRUE(fs::exists(dir / "s/sweep.png")) << name << ": " << r.plot_note;
    }
    EXPECT_FALSE(fs::exists(dir / "owned")) << name;
    EXPECT_FALSE(fs::exists(dir / "s/owned")) << name;
    fs::remove_all(dir / "s");
  }
  fs::current_path(cwd);
}

TEST(Sweep, ABadValueStopsTheSweepBeforeAnythingRuns) {
  test::TempDir dir;
  SweepOptions o = single_joint_sweep(dir / "s");
  o.axes = {parse_sweep_axis("solid.fracture.integration_points=3,5")};
  try {
    run_sweep(o);
    FAIL() << "integration_points = 5 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("integration_points"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "s"));
}

}  // namespace
}  // namespace rift
