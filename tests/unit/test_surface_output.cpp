// The surface mesh in a run's output (issue 5): written as the grid "surface" when the scene asks for
// it (output.surface), absent otherwise (no conversion model at all), with fracture triangles tagged
// and timed, counts in summary.json, and a restart that writes the same surface as a straight run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/io/hdf5_file.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/mesh_conversion_model.hpp"
#include "systems/simulation.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

// One joint between two tets, opened until it breaks (at about t = 1.8e-3 s of 2e-3 s).
Scene single_joint(std::vector<std::string> overrides) {
  overrides.push_back("output.interval=5.0e-4");
  return load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/single_joint_mode_I.yaml", overrides);
}

using test::run_scene;

nlohmann::json summary_of(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

// The last output file of a series (rift_<step>.h5, the highest step).
fs::path last_output(const fs::path& dir) {
  fs::path best;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("rift_", 0) == 0 && name.ends_with(".h5") && name.find("mesh") == std::string::npos &&
        name > best.filename().string())
      best = e.path();
  }
  return best;
}

TEST(SurfaceOutput, OnlyWhenTheSceneAsksForIt) {
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  Simulation without(single_joint({}), o);
  for (const auto& m : without.world().models) EXPECT_EQ(m->name(), "solid");
  Simulation with(single_joint({"output.surface=true"}), o);
  ASSERT_EQ(with.world().models.size(), 2u);
  EXPECT_EQ(with.world().models[1]->name(), "mesh_conversion");
}

TEST(SurfaceOutput, FractureTrianglesAreWrittenWithTheirTime) {
  test::TempDir dir;
  const RunResult r = run_scene(single_joint({"output.surface=true"}), dir.path(), 1);
  ASSERT_TRUE(r.completed);
  const std::string xdmf = test::slurp(dir / "rift.xdmf");
  EXPECT_NE(xdmf.find("Name=\"surface\""), std::string::npos);
  const auto s = summary_of(dir.path())["metrics"]["mesh_conversion"];
  EXPECT_EQ(s["external_triangles"], 6);  // two tets: 4 faces each, minus the two the joint ties
  EXPECT_EQ(s["fracture_triangles"], 2);
  EXPECT_EQ(s["fragments"], 2);
  EXPECT_EQ(s["fracture_surfaces"], 1);

  const H5File last(last_output(dir.path()), H5File::Mode::read);
  const auto tag = last.read<uint8_t>("/surface/tag");
  const auto when = last.read<double>("/surface/fracture_time");
  ASSERT_EQ(tag.size(), 8u);
  for (size_t t = 0; t < tag.size(); ++t) {
    EXPECT_EQ(tag[t] == static_cast<uint8_t>(SurfaceTag::fracture), t >= 6);
    if (t >= 6) {
      EXPECT_GT(when[t], 1.0e-3);  // opened at 0.01 m/s, it breaks after o = 1.8e-5 m
      EXPECT_LT(when[t], 2.0e-3);
    } else {
      EXPECT_EQ(when[t], -1.0);
    }
  }
}

TEST(SurfaceOutput, RestartWritesTheSameSurface) {
  test::TempDir straight_dir, restarted_dir;
  const Scene scene = single_joint({"output.surface=true"});
  const RunResult straight = run_scene(scene, straight_dir.path(), 2);
  ASSERT_TRUE(straight.completed);
  const int64_t stop = straight.steps * 19 / 20;  // after the break
  run_scene(scene, restarted_dir.path(), 2, stop);
  const RunResult resumed = run_scene(scene, restarted_dir.path(), 1, std::nullopt, true);
  ASSERT_TRUE(resumed.completed);
  EXPECT_EQ(summary_of(straight_dir.path())["metrics"]["mesh_conversion"],
            summary_of(restarted_dir.path())["metrics"]["mesh_conversion"]);
  const H5File a(last_output(straight_dir.path()), H5File::Mode::read);
  const H5File b(last_output(restarted_dir.path()), H5File::Mode::read);
  EXPECT_EQ(a.read<double>("/surface/points"), b.read<double>("/surface/points"));
  EXPECT_EQ(a.read<double>("/surface/fracture_time"), b.read<double>("/surface/fracture_time"));
  EXPECT_EQ(a.read<int32_t>("/surface/joint"), b.read<int32_t>("/surface/joint"));
}

}  // namespace
}  // namespace rift
