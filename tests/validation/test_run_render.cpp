// `rift render` (engine/render) on a run whose crack is known: the column of
// scenes/validation/contact_cut_column.yaml is cut at set-up on the plane z = 20 mm, half its height. A
// cut along y, seen with z up, must show the crack trace as one horizontal black line across the column at
// the picture's middle (ParaView centres the cut), the field's colours above and below it, and a PNG of
// the size asked for; the cracks picture shows the broken joints in colour. A field the run does not have
// and a folder that is not a run are refused with status 2 and a message naming what there is. Skipped,
// saying so, without pvpython and xvfb-run or without a python3 that reads PNGs (matplotlib).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/spawn.hpp"
#include "engine/scene/load_scene.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

// argv: the cut picture, the cracks picture, width, height. Columns 45-60 % of the width hold the column
// and nothing else (the caption ends left of them, the colour bar starts right of them).
constexpr const char* kCheckPictures = R"py(
import sys
import numpy as np
import matplotlib.image as image
cut, cracks, width, height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
a = image.imread(cut)[:, :, :3]
assert a.shape[:2] == (height, width), a.shape
band = a[:, int(0.45 * width):int(0.60 * width)]
black = band.max(axis=2) < 0.15
white = band.min(axis=2) > 0.95
coloured = ~black & ~white
rows = np.nonzero(black.any(axis=1))[0]
print(f"black rows {rows.min() if len(rows) else None}..{rows.max() if len(rows) else None} of {height}")
assert len(rows) > 0, "no crack trace"
assert abs(rows.mean() - height / 2) < 0.03 * height and rows.max() - rows.min() < 0.02 * height, rows
assert black[rows].any(axis=0).mean() > 0.9, "the trace does not cross the band"
above, below = coloured[: rows.min()].any(axis=1).sum(), coloured[rows.max() + 1:].any(axis=1).sum()
print(f"coloured rows above {above}, below {below}")
assert above > 0.3 * height and below > 0.3 * height
b = image.imread(cracks)[:, :, :3]
assert b.shape[:2] == (height, width), b.shape
spread = b.max(axis=2) - b.min(axis=2)  # viridis is saturated, the outline and the text are grey
print(f"saturated pixels in the cracks picture: {(spread > 0.3).mean():.3f}")
assert (spread > 0.3).mean() > 0.002
)py";

bool has_paraview() {
  return !find_program("pvpython").empty() && (!find_program("xvfb-run").empty() || std::getenv("DISPLAY"));
}

int rift_cli(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> argv = {RIFT_EXECUTABLE};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_program(argv, {}, log);
}

TEST(RunRender, TheCutShowsTheKnownCrackAsALineAcrossTheColumn) {
  const std::string py = python_with("matplotlib, numpy");
  if (!has_paraview() || py.empty())
    GTEST_SKIP() << "SKIP: pvpython with xvfb-run (Debian: apt-get install paraview python3-paraview xvfb) "
                    "or python3-matplotlib not installed; rift render not checked";
  test::TempDir dir;
  const Scene scene = load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/contact_cut_column.yaml",
                                 {"time.end=2.0e-4", "output.interval=1.0e-4"});
  ASSERT_TRUE(test::run_scene(scene, dir / "run", 1).completed);

  const fs::path log = dir / "render.log";
  ASSERT_EQ(rift_cli({"render", (dir / "run").string(), "--normal", "y", "--field", "stress:zz", "--size",
                      "640x480", "--out", (dir / "pictures").string()},
                     log),
            0)
      << test::slurp(log) << test::slurp(dir / "pictures" / "render_run.log");
  const fs::path cut = dir / "pictures" / "cut_stress_zz_0002.png";
  const fs::path cracks = dir / "pictures" / "cracks_0002.png";
  ASSERT_TRUE(fs::is_regular_file(cut)) << test::slurp(log);
  ASSERT_TRUE(fs::is_regular_file(cracks)) << test::slurp(log);
  std::ofstream(dir / "check.py") << kCheckPictures;
  const fs::path check_log = dir / "check.log";
  EXPECT_EQ(run_program({py, (dir / "check.py").string(), cut.string(), cracks.string(), "640", "480"}, {},
                        check_log),
            0);
  std::printf("%s", test::slurp(check_log).c_str());

  // A field the run does not write: refused, naming the fields it has.
  const fs::path bad_log = dir / "bad.log";
  EXPECT_EQ(rift_cli({"render", (dir / "run").string(), "--field", "pressure"}, bad_log), 2);
  const std::string bad = test::slurp(bad_log);
  EXPECT_NE(bad.find("no field 'pressure'"), std::string::npos) << bad;
  EXPECT_NE(bad.find("stress"), std::string::npos) << bad;
  // A component the field does not have.
  EXPECT_EQ(rift_cli({"render", (dir / "run").string(), "--field", "stress:qq"}, bad_log), 2);
  EXPECT_NE(test::slurp(bad_log).find("xx, xy, xz"), std::string::npos) << test::slurp(bad_log);
}

TEST(RunRender, AFolderThatIsNotARunIsRefused) {
  test::TempDir dir;
  const fs::path log = dir / "render.log";
  EXPECT_EQ(rift_cli({"render", dir.path().string()}, log), 2);
  EXPECT_NE(test::slurp(log).find("rift.series.json"), std::string::npos) << test::slurp(log);
}

}  // namespace
}  // namespace rift
