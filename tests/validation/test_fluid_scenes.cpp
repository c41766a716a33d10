// The fluid scenes run through the Simulation as `rift run` runs them: the lid-driven cavity against
// Ghia et al. (1982) (scenes/examples/cavity.yaml; the same setup as test_fluid_cavity.cpp, which drives
// the solver directly) and the pressure-driven channel against Poiseuille
// (scenes/validation/poiseuille.yaml).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "engine/scene/load_scene.hpp"
#include "engine/sweep/reference_metrics.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"
#include "tests/validation/ghia1982.hpp"

namespace rift {
namespace {

nlohmann::json summary_of(const std::filesystem::path& dir) {
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

// 16 x 16 cells, 300 steps of 0.1 to t = 30 (steady by t ~ 23): the bound is 0.02. The scene
// reads Ghia's points with probes; its table is checked against this test's own transcription
// (ghia1982.hpp), so a typo in either shows.
TEST(FluidScenes, CavityAgainstGhia) {
  test::TempDir dir;
  const Scene scene = load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/examples/cavity.yaml");
  const fluid_test::GhiaTable& ghia = fluid_test::ghia_table(100);
  ASSERT_EQ(scene.probes.size(), 2u);
  for (size_t k = 1; k < 16; ++k) {
    const ProbePointSpec& u = scene.probes[0].points[k - 1];
    const ProbePointSpec& v = scene.probes[1].points[k - 1];
    EXPECT_EQ(u.at, (std::array<double, 3>{0.5, fluid_test::kGhiaY[k], 0.0}));
    EXPECT_EQ(u.value, ghia.u[k]);
    EXPECT_EQ(v.at, (std::array<double, 3>{fluid_test::kGhiaX[k], 0.5, 0.0}));
    EXPECT_EQ(v.value, ghia.v[k]);
  }
  const RunResult r = test::run_scene(scene, dir / "cavity", 1);
  ASSERT_TRUE(r.completed);
  const auto metrics = summary_of(dir / "cavity")["metrics"];
  const double du = metrics["probes"]["ghia_u"]["max_error"].get<double>();
  const double dv = metrics["probes"]["ghia_v"]["max_error"].get<double>();
  std::printf("cavity scene: max |du| %.4f, max |dv| %.4f, %lld steps in %.2f s, max cfl %.3f\n", du, dv,
              static_cast<long long>(r.steps), r.wall_seconds, metrics["fluid"]["max_cfl"].get<double>());
  EXPECT_LE(du, 0.02);
  EXPECT_LE(dv, 0.02);
  EXPECT_EQ(metrics["probes"]["ghia_u"]["compared"].get<int>(), 15);
  // The scene's reference metrics read the same numbers.
  const auto reference = read_reference_metrics(scene.reference, dir / "cavity");
  ASSERT_EQ(reference.size(), 2u);
  ASSERT_TRUE(reference[0].value && reference[1].value);
  EXPECT_DOUBLE_EQ(*reference[0].value, du);
  EXPECT_DOUBLE_EQ(*reference[1].value, dv);
}

// Steady centre speed G H^2 / (8 mu) = 1 m/s within 1 %.
TEST(FluidScenes, PoiseuilleCentreSpeed) {
  test::TempDir dir;
  const Scene scene = load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/poiseuille.yaml");
  const RunResult r = test::run_scene(scene, dir / "channel", 1);
  ASSERT_TRUE(r.completed);
  const auto metrics = read_reference_metrics(scene.reference, dir / "channel");
  ASSERT_EQ(metrics.size(), 1u);
  ASSERT_TRUE(metrics[0].value);
  const auto f = summary_of(dir / "channel")["metrics"]["fluid"];
  std::printf(
      "poiseuille scene: centre speed %.6f m/s (exact 1), %lld steps in %.2f s, picard failures %lld, "
      "last step %lld Picard %lld FGMRES\n",
      *metrics[0].value, static_cast<long long>(r.steps), r.wall_seconds,
      static_cast<long long>(f["picard_failures"].get<int64_t>()),
      static_cast<long long>(f["last_step"]["picard_iterations"].get<int64_t>()),
      static_cast<long long>(f["last_step"]["schur_iterations"].get<int64_t>()));
  EXPECT_NEAR(*metrics[0].value, 1.0, 0.01);
  EXPECT_EQ(f["picard_failures"].get<int64_t>(), 0);
}

}  // namespace
}  // namespace rift
