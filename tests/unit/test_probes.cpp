// Probes: the point location kernel (P1 interpolation reproduces a linear field exactly), and gauges in a
// run, checked against a motion known in closed form (a free body in uniform translation).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/scene/load_scene.hpp"
#include "kernels/tet_point_location.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift {
namespace {

// The unit cube as six tets around its main diagonal (Kuhn's split), nodes at the cube's corners.
struct Cube {
  std::vector<double> x;
  std::vector<int32_t> tets;
  Cube() {
    for (int k = 0; k < 8; ++k)
      for (int d = 0; d < 3; ++d) x.push_back((k >> d) & 1);
    const int paths[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
    for (const auto& p : paths) {  // 0 -> 0+a -> 0+a+b -> 7
      tets.insert(tets.end(), {0, p[0], p[0] | p[1], 7});
    }
  }
};

double linear(const double* p) {
  return 1.5 - 2.0 * p[0] + 0.25 * p[1] + 3.0 * p[2];
}

TEST(TetPointLocation, InterpolationReproducesALinearFieldAnywhereInTheMesh) {
  const Cube cube;
  std::vector<double> field;
  for (size_t n = 0; n < 8; ++n) field.push_back(linear(&cube.x[3 * n]));
  const double points[][3] = {{0.1, 0.2, 0.3}, {0.9, 0.05, 0.5}, {0.5, 0.5, 0.5},  // inside
                              {0.3, 0.3, 0.8}, {0.0, 0.0, 0.0},  {1.0, 1.0, 1.0},  // a face, corners
                              {0.25, 0.7, 0.0}};                                   // a boundary face
  for (const auto& q : points) {
    const kernels::TetPointLocation at = kernels::locate_in_tets(q, cube.x, cube.tets, 0.0);
    ASSERT_GE(at.tet, 0);
    EXPECT_GE(at.lowest, -1e-15);
    EXPECT_NEAR(at.lambda[0] + at.lambda[1] + at.lambda[2] + at.lambda[3], 1.0, 1e-15);
    // Exact up to round-off: P1 holds linear fields; a few ulps of values of order 5.
    EXPECT_NEAR(kernels::interpolate_p1(at, cube.tets, field, 1, 0), linear(q), 1e-14);
  }
}

TEST(TetPointLocation, SaysHowFarOutsideAPointIs) {
  const Cube cube;
  const double q[3] = {1.5, 0.5, 0.5};
  EXPECT_EQ(kernels::locate_in_tets(q, cube.x, cube.tets, 0.0).tet, -1);  // no bounding box holds it
  const kernels::TetPointLocation near = kernels::locate_in_tets(q, cube.x, cube.tets, 1.0);
  ASSERT_GE(near.tet, 0);
  EXPECT_LT(near.lowest, -0.4);
}

// A free block in uniform translation: no force acts, so x = x0 + v t and the velocity is v exactly.
Scene translating_block(const std::string& probe_point) {
  const std::string yaml = R"(
scene: {name: probes}
time: {end: 1.0e-4}
mesh:
  generate: {box: [0.1, 0.05, 0.05], cells: [4, 2, 2]}
solid:
  materials: [{name: rock, density: 2700, young: 6.0e10, poisson: 0.25}]
  initial_velocity: [{regions: [all], velocity: [0.3, -0.2, 0.1]}]
output: {interval: 5.0e-5}
probes:
  - name: speed
    field: solid.velocity
    component: magnitude
    points: [{at: )" + probe_point +
                           R"(, value: 0.37416573867739417}]
  - name: moved
    field: solid.displacement
    component: x
    factor: 1.0e3
    points: [{at: [0.01, 0.01, 0.01]}, {at: [0.1, 0.05, 0.05], value: 0.03}]
  - name: line
    field: solid.displacement
    component: x
    line: {from: [0.0, 0.0, 0.0], to: [0.1, 0.05, 0.05], count: 5}
  - name: sxx
    field: solid.stress
    component: xx
    points: [{at: [0.05, 0.025, 0.025], value: 0.0}]
)";
  SceneLoadResult r = read_scene_text(yaml, "probes.yaml", ".");
  if (!r.scene) throw Error(r.errors.front().format());
  return *r.scene;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) out.push_back(cell);
  return out;
}

TEST(Probes, ReadTheSolidAtPointsThatMoveWithIt) {
  test::TempDir dir;
  const RunResult r = test::run_scene(translating_block("[0.05, 0.025, 0.025]"), dir / "run", 1);
  ASSERT_TRUE(r.completed);
  std::ifstream in(dir / "run" / "summary.json");
  const auto probes = nlohmann::json::parse(in)["metrics"]["probes"];
  // |v| = sqrt(0.09 + 0.04 + 0.01); x displacement at t = 1e-4 s: 0.3 x 1e-4 m = 0.03 mm (factor 1e3).
  // Tolerances: the round-off of a rigid motion's elastic forces (F = I + O(1e-16), times E = 6e10 Pa)
  // integrated over 59 steps, about 1e-11 relative.
  EXPECT_NEAR(probes["speed"]["values"][0].get<double>(), std::sqrt(0.14), 1e-11);
  EXPECT_NEAR(probes["moved"]["values"][0].get<double>(), 0.03, 1e-12);
  EXPECT_NEAR(probes["moved"]["values"][1].get<double>(), 0.03, 1e-12);
  EXPECT_EQ(probes["moved"]["compared"].get<int>(), 1);
  EXPECT_LT(probes["moved"]["max_error"].get<double>(), 1e-12);
  EXPECT_LT(std::abs(probes["sxx"]["values"][0].get<double>()), 1e-3);  // Pa, against a 6e10 Pa modulus
  // A line of 5 points, corner to corner, each moved by 0.3 x 1e-4 m.
  ASSERT_EQ(probes["line"]["values"].size(), 5u);
  for (const auto& v : probes["line"]["values"]) EXPECT_NEAR(v.get<double>(), 3e-5, 1e-15);
  EXPECT_FALSE(probes["line"].contains("max_error"));  // no known values
  // Every point is a time-series column, sampled at every row.
  std::ifstream csv(dir / "run" / "timeseries.csv");
  std::string header, row, last;
  std::getline(csv, header);
  while (std::getline(csv, row))
    if (!row.empty()) last = row;
  const auto names = split(header), values = split(last);
  ASSERT_EQ(names.size(), values.size());
  for (const char* column : {"probe_speed", "probe_moved_0", "probe_moved_1", "probe_sxx"}) {
    const auto it = std::find(names.begin(), names.end(), column);
    ASSERT_NE(it, names.end()) << column;
    if (std::string(column) == "probe_moved_1") {
      EXPECT_NEAR(std::stod(values[it - names.begin()]), 0.03, 1e-12);
    }
  }
}

TEST(Probes, APointOutsideTheSolidStopsTheRunBeforeItStarts) {
  test::TempDir dir;
  try {
    test::run_scene(translating_block("[0.05, 0.025, 0.06]"), dir / "run", 1);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("point 0 of 'speed' at (0.05, 0.025, 0.06) lies outside the solid"),
              std::string::npos)
        << what;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "run" / "summary.json"));
}

}  // namespace
}  // namespace rift
