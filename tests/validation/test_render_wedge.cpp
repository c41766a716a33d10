// scripts/render_wedge.py (the Fig. 7 panels of Guo et al. 2015) on a tiny run of the wedge scene
// (scenes/examples/guo2015_wedge.yaml, 8 / 16 mm tets, 5 us): the stress panel is a PNG of the pixel size
// the script promises (its FIGSIZE_IN x DPI), and a folder that is not a run is refused with status 2.
// Nothing about the look. Skipped without a python3 that has matplotlib and h5py.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/spawn.hpp"
#include "engine/scene/load_scene.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

const std::string kScript = std::string(RIFT_SOURCE_DIR) + "/scripts/render_wedge.py";

// The size render_wedge.py promises for the stress panel: 8.0 x 6.0 in at 120 dpi.
constexpr uint32_t kStressWidth = 960, kStressHeight = 720;

// The first Python with what the script needs: the one on PATH, else Debian's (pyenv may shadow it).
std::string python_with_plotting() {
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (run_program({py, "-c", "import matplotlib, h5py, numpy"}) == 0) return py;
  return "";
}

uint32_t big_endian_u32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

std::vector<fs::path> files_starting_with(const fs::path& dir, const std::string& prefix) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(prefix, 0) == 0) found.push_back(e.path());
  return found;
}

TEST(RenderWedge, TheStressPanelOfATinyRunIsAPngOfThePromisedSize) {
  const std::string py = python_with_plotting();
  if (py.empty())
    GTEST_SKIP() << "no python3 with matplotlib and h5py (Debian: apt-get install python3-matplotlib "
                    "python3-h5py): render_wedge.py not tested";
  test::TempDir dir;
  const Scene scene = load_scene(
      std::string(RIFT_SOURCE_DIR) + "/scenes/examples/guo2015_wedge.yaml",
      {"mesh.generate.size_min=0.008", "mesh.generate.size_max=0.016", "fluid.mesh.generate.size_min=0.008",
       "solid.mass_scaling_step=1.0e-8", "time.end=5.0e-6", "output.interval=2.5e-6"});
  ASSERT_TRUE(test::run_scene(scene, dir / "run", 1).completed);

  // The last output (5 us = 0.005 ms), one panel, through an argument vector.
  const fs::path log = dir / "render.log";
  const int status = run_program({py, kScript, (dir / "run").string(), "--out", (dir / "fig").string(),
                                  "--times", "0.005", "--only", "stress"},
                                 {}, log);
  ASSERT_EQ(status, 0) << test::slurp(log);
  const auto pngs = files_starting_with(dir / "fig", "stress_");
  ASSERT_EQ(pngs.size(), 1u) << test::slurp(log);
  EXPECT_TRUE(files_starting_with(dir / "fig", ".").empty()) << "a temporary file was left behind";

  // The signature, then the IHDR chunk: length, "IHDR", width, height (big-endian).
  const std::string png = test::slurp(pngs[0]);
  ASSERT_GE(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(big_endian_u32(png, 16), kStressWidth);
  EXPECT_EQ(big_endian_u32(png, 20), kStressHeight);
}

TEST(RenderWedge, AFolderThatIsNotARunIsRefusedWithStatus2) {
  const std::string py = python_with_plotting();
  if (py.empty()) GTEST_SKIP() << "no python3 with matplotlib and h5py: render_wedge.py not tested";
  test::TempDir dir;
  const fs::path log = dir / "render.log";
  EXPECT_EQ(run_program({py, kScript, dir.path().string()}, {}, log), 2);
  EXPECT_NE(test::slurp(log).find("rift.series.json"), std::string::npos) << test::slurp(log);
}

}  // namespace
}  // namespace rift
