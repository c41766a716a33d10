// The graded lattice (mesh.generate.graded): cells of `size` in a fine box, growing by `growth` per cell
// outside it. Checked: the fine spacing and the box ends are exact, neighbouring cells outside grow by
// the ratio (the last one stretched within its stated range), the count matches the one the budget uses,
// a mirror-symmetric box gives mirror-symmetric nodes, every tet is positive, and a starter penny crack
// on a fine lattice plane builds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/vec3.hpp"
#include "engine/mesh/graded_axis.hpp"
#include "engine/mesh/structured_box.hpp"
#include "engine/scene/load_scene.hpp"
#include "engine/world.hpp"
#include "systems/world_builder.hpp"

namespace rift {
namespace {

TEST(GradedLattice, FineCellsAreExactAndTheOthersGrowByTheRatio) {
  const std::vector<double> x = graded_axis(0.0, 10.0, -1.0, 2.5, 0.125, 1.3);
  ASSERT_EQ(x.front(), 0.0);
  ASSERT_EQ(x.back(), 10.0);
  for (int k = 0; k <= 20; ++k) EXPECT_EQ(x[static_cast<size_t>(k)], 2.5 * k / 20) << k;
  double previous = 0.125;
  for (size_t i = 21; i + 1 < x.size(); ++i) {
    const double h = x[i] - x[i - 1];
    EXPECT_NEAR(h / previous, 1.3, 1e-12) << i;
    previous = h;
  }
  const double last = x.back() - x[x.size() - 2];
  EXPECT_GE(last, 0.5 * previous * 1.3);  // the rest: between half and one and a half nominal cells
  EXPECT_LE(last, 1.5 * previous * 1.3);
  EXPECT_LT(x.size(), 35u);  // 20 fine cells and a dozen growing ones for 7.5 m
}

// With max_size the cells grow to it and stay there; the count still matches, the ends are exact, and
// without it the axis is the uncapped one.
TEST(GradedLattice, CappedCellsGrowToTheCapAndStay) {
  const std::vector<double> x = graded_axis(0.0, 10.0, -1.0, 2.5, 0.125, 1.3, 0.5);
  ASSERT_EQ(x.size(), graded_axis_nodes(0.0, 10.0, -1.0, 2.5, 0.125, 1.3, 0.5));
  ASSERT_EQ(x.front(), 0.0);
  ASSERT_EQ(x.back(), 10.0);
  double previous = 0.125;
  for (size_t i = 21; i + 1 < x.size(); ++i) {
    const double h = x[i] - x[i - 1];
    EXPECT_NEAR(h, std::min(1.3 * previous, 0.5), 1e-12) << i;
    previous = h;
  }
  const double last = x.back() - x[x.size() - 2];
  EXPECT_GE(last, 0.25);  // the rest: between half and one and a half capped cells
  EXPECT_LE(last, 0.75);
  EXPECT_EQ(graded_axis(0.0, 10.0, -1.0, 2.5, 0.125, 1.3),
            graded_axis(0.0, 10.0, -1.0, 2.5, 0.125, 1.3, 1e300));
  EXPECT_THROW(graded_axis(0.0, 10.0, -1.0, 2.5, 0.125, 1.3, 0.1), Error);  // a cap below the fine size
}

TEST(GradedLattice, TheCountIsTheBudgetsAndTheAxisIncreases) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int c = 0; c < 2000; ++c) {
    const double lo = -10 * u(rng), hi = lo + 0.01 + 20 * u(rng);
    const double a = lo - 1 + (hi - lo + 2) * u(rng), b = a + 0.001 + 5 * u(rng);
    if (!(b > lo && a < hi)) continue;
    const double size = 0.01 + 0.5 * u(rng), growth = 1.0 + u(rng);
    const std::vector<double> x = graded_axis(lo, hi, a, b, size, growth);
    ASSERT_EQ(x.size(), graded_axis_nodes(lo, hi, a, b, size, growth)) << c;
    ASSERT_EQ(x.front(), lo);
    ASSERT_EQ(x.back(), hi);
    for (size_t i = 1; i < x.size(); ++i) ASSERT_GT(x[i], x[i - 1]) << c << " " << i;
  }
}

TEST(GradedLattice, AMirrorSymmetricBoxGivesMirrorSymmetricNodesWithTheMidPlane) {
  const std::vector<double> x = graded_axis(-8.0, 8.0, -0.25, 0.25, 0.125, 1.25);
  ASSERT_EQ(x.size() % 2, 1u);
  for (size_t i = 0; i < x.size(); ++i) EXPECT_EQ(x[i], -x[x.size() - 1 - i]) << i;
  EXPECT_EQ(x[x.size() / 2], 0.0);
}

TEST(GradedLattice, EveryTetIsPositiveAndTheBoxIsFilled) {
  const auto axes = graded_lattice_axes({0, 0, -4}, {6, 6, 8}, {-1, -1, -0.25}, {2, 2, 0.25}, 0.125, 1.3);
  const TetMesh mesh = structured_box_on_axes(axes);
  EXPECT_EQ(mesh.tets.size(), 6 * (axes[0].size() - 1) * (axes[1].size() - 1) * (axes[2].size() - 1));
  double volume = 0.0;
  for (const auto& t : mesh.tets) {
    const Vec3 e1 = sub(mesh.nodes[t[1]], mesh.nodes[t[0]]), e2 = sub(mesh.nodes[t[2]], mesh.nodes[t[0]]),
               e3 = sub(mesh.nodes[t[3]], mesh.nodes[t[0]]);
    const double six_v = dot(e1, cross(e2, e3));
    ASSERT_GT(six_v, 0.0);
    volume += six_v / 6.0;
  }
  EXPECT_NEAR(volume, 6.0 * 6.0 * 8.0, 1e-9 * 288.0);
}

std::string scene_errors(const std::string& generate) {
  const std::string yaml =
      "scene: {name: g}\ntime: {end: 1.0e-6}\nmesh:\n  generate:\n" + generate +
      "solid:\n  materials:\n    - {name: rock, density: 2500, young: 1.0e10, poisson: 0.25}\n";
  const SceneLoadResult r = read_scene_text(yaml, "g.yaml", ".");
  std::string all;
  for (const auto& e : r.errors) all += e.key_path + ": expected " + e.expected + ", found " + e.found + "\n";
  return all;
}

TEST(GradedLattice, TheSceneKeysAreCheckedAndAStarterPennyBuilds) {
  const std::string box = "    box: [4, 4, 8]\n    origin: [0, 0, -4]\n";
  EXPECT_EQ(
      scene_errors(box + "    graded: {fine_min: [0, 0, -0.25], fine_max: [1, 1, 0.25], size: 0.125}\n"), "");
  EXPECT_NE(
      scene_errors(box + "    graded: {fine_min: [5, 0, -0.25], fine_max: [6, 1, 0.25], size: 0.125}\n")
          .find("mesh.generate.graded.fine_max: expected a fine box that overlaps the box along x (0, 4)"),
      std::string::npos);
  EXPECT_NE(scene_errors(box + "    graded: {fine_min: [0, 0, -0.25], fine_max: [1, 1, 0.25], size: 0.1, "
                               "growth: 3}\n")
                .find("mesh.generate.graded.growth"),
            std::string::npos);
  EXPECT_NE(scene_errors(box + "    cells: [2, 2, 2]\n    graded: {fine_min: [0, 0, 0], fine_max: [1, 1, 1], "
                               "size: 0.1}\n")
                .find("mesh.generate.cells"),
            std::string::npos);
  EXPECT_NE(
      scene_errors(box + "    graded: {fine_min: [0, 0, -0.25], fine_max: [1, 1, 0.25], size: 1.0e-9}\n")
          .find("mesh.generate.graded.size: expected at most 1e6 cells across the fine box"),
      std::string::npos);

  // A quarter penny on the fine plane z = 0, from the same scene definition the CLI reads.
  const std::string yaml =
      "scene: {name: g}\ntime: {end: 1.0e-6}\nmesh:\n  generate:\n" + box +
      "    graded: {fine_min: [0, 0, -0.25], fine_max: [1.5, 1.5, 0.25], size: 0.125}\n"
      "solid:\n  materials:\n    - name: rock\n      density: 2500\n      young: 1.0e10\n      poisson: "
      "0.25\n"
      "      fracture: {tensile_strength: 1.0e6, cohesion: 1.0e7, friction_angle: 30, G_I: 100, G_II: 1000}\n"
      "  fracture:\n    box_min: [-1, -1, -0.13]\n    box_max: [2, 2, 0.13]\n"
      "    initial_cracks:\n      - {point: [0, 0, 0], normal: [0, 0, 1], radius: 0.5}\n";
  const SceneLoadResult r = read_scene_text(yaml, "g.yaml", ".");
  ASSERT_TRUE(r.scene.has_value()) << (r.errors.empty() ? ""
                                                        : r.errors[0].key_path + " " + r.errors[0].expected);
  const TetMesh mesh = load_mesh(r.scene->mesh);
  const auto n = graded_lattice_nodes({0, 0, -4}, {4, 4, 8}, {0, 0, -0.25}, {1.5, 1.5, 0.25}, 0.125, 1.25);
  EXPECT_EQ(mesh.tets.size(), 6 * (n[0] - 1) * (n[1] - 1) * (n[2] - 1));
  const auto world = build_world(*r.scene);
  EXPECT_GT(world->store.table("solid_fracture_event").size(), 0u);  // the starter crack's joints
}

}  // namespace
}  // namespace rift
