// The paper's observations (Guo et al. 2015, section 5) on the coupled wedge's coarse preset
// (scenes/examples/guo2015_wedge.yaml: 4 / 8 mm tets, 4 mm fluid cells at the notch, mass scaling 1e-8 s),
// the part of them that holds up to the first breaks:
//  - no joint breaks while the inlet holds 15 MPa (0.1 ms), nor while it holds 14 MPa for as long;
//  - the crack starts after the ramp begins, at the notch's tip (its first break within two elements,
//    8 mm, of the tip's line x = 24.5 mm, y = 50 mm), and runs close to the notch's plane (the broken
//    joints' RMS distance from y = 50 mm below two elements, 8 mm) to 0.15 ms.
// Tolerances in elements: a crack can only follow the tets' faces, so its path and its first break are
// known to the element's size and no closer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"
#include "tests/validation/paper_wedge_support.hpp"

namespace rift {
namespace {

constexpr double kElement = 0.008;                     // the coarse preset's largest tet
constexpr double kTipX = 0.0245, kNotchPlaneY = 0.05;  // the notch's tip line (through z)
constexpr double kRampStart = 1.0e-4;

// No field outputs: the breaks are read from fractures.csv.
Scene coarse_wedge(std::vector<std::string> more) {
  more.push_back("output.interval=1.0e-3");
  return validation::coupled_wedge_coarse(more);
}

struct Break {
  double time, x, y, z;
};

// fractures.csv: step,time,joint,tet_a,tet_b,mode,x,y,z,...
std::vector<Break> breaks_of(const std::filesystem::path& run) {
  std::ifstream in(run / "fractures.csv");
  std::string line;
  std::getline(in, line);
  std::vector<Break> out;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::vector<std::string> cell;
    for (std::string c; std::getline(s, c, ',');) cell.push_back(c);
    out.push_back({std::stod(cell[1]), std::stod(cell[6]), std::stod(cell[7]), std::stod(cell[8])});
  }
  return out;
}

TEST(PaperWedgeObservations, NoBreakAt14MPaHeldForTheSettlingsTime) {
  test::TempDir dir;
  const Scene scene = coarse_wedge(
      {"time.end=1.0e-4", "fluid.initial_pressure=1.4e7", "fluid.boundaries[0].value.ramp.value=1.4e7"});
  ASSERT_TRUE(test::run_scene(scene, dir / "run", 2).completed);
  EXPECT_TRUE(breaks_of(dir / "run").empty());
}

TEST(PaperWedgeObservations, TheCrackStartsAtTheTipAfterTheRampAndRunsInTheNotchsPlane) {
  test::TempDir dir;
  const Scene scene = coarse_wedge({"time.end=1.5e-4"});
  ASSERT_TRUE(test::run_scene(scene, dir / "run", 2).completed);
  const std::vector<Break> breaks = breaks_of(dir / "run");
  ASSERT_FALSE(breaks.empty()) << "no break by 0.15 ms (0.05 ms into the ramp)";
  const Break& first = breaks.front();
  double sq = 0.0;
  for (const Break& b : breaks) sq += (b.y - kNotchPlaneY) * (b.y - kNotchPlaneY);
  const double rms = std::sqrt(sq / double(breaks.size()));
  std::printf(
      "first break at %.4g ms, (%.4g, %.4g, %.4g) mm; %zu broken by 0.15 ms, RMS off the plane %.3g mm\n",
      first.time * 1e3, first.x * 1e3, first.y * 1e3, first.z * 1e3, breaks.size(), rms * 1e3);
  EXPECT_GT(first.time, kRampStart);  // none while the inlet holds 15 MPa
  EXPECT_LT(std::hypot(first.x - kTipX, first.y - kNotchPlaneY), 2 * kElement);
  EXPECT_LT(rms, 2 * kElement);
}

}  // namespace
}  // namespace rift
