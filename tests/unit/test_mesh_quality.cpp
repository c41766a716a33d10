// Mesh quality measures against tets whose values are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine/mesh/mesh_quality.hpp"

namespace rift {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;
// Closed-form values computed with a handful of double operations: a few ulps of error.
constexpr double kTol = 1e-13;

TEST(MeshQuality, RegularTet) {
  // Alternate corners of the cube [-1, 1]^3: edges 2 sqrt(2), volume 8/3.
  const TetShape s = tet_shape({1, 1, 1}, {-1, 1, -1}, {1, -1, -1}, {-1, -1, 1});
  EXPECT_NEAR(s.six_volume, 16.0, kTol);
  EXPECT_NEAR(s.radius_ratio, 1.0, kTol);
  const double dihedral = std::acos(1.0 / 3.0);  // 70.5288 degrees
  EXPECT_NEAR(s.min_dihedral_rad, dihedral, kTol);
  EXPECT_NEAR(s.max_dihedral_rad, dihedral, kTol);
  EXPECT_NEAR(s.min_dihedral_rad * kDeg, 70.5288, 1e-4);
  EXPECT_NEAR(s.min_edge, 2 * std::sqrt(2.0), kTol);
  EXPECT_NEAR(s.max_edge, 2 * std::sqrt(2.0), kTol);
  EXPECT_NEAR(s.circumradius, std::sqrt(3.0), kTol);  // the cube's half-diagonal
  for (const double c : s.circumcenter) EXPECT_NEAR(c, 0.0, kTol);
}

TEST(MeshQuality, RightCornerTet) {
  // Unit corner: three right dihedral angles at the axes, acos(1/sqrt 3) = 54.7356 deg at the slanted
  // face; inradius 1 / (3 + sqrt 3), circumradius sqrt(3)/2, so 3 r / R = sqrt(3) - 1.
  const TetShape s = tet_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_NEAR(s.six_volume, 1.0, kTol);
  EXPECT_NEAR(s.radius_ratio, std::sqrt(3.0) - 1.0, kTol);
  EXPECT_NEAR(s.min_dihedral_rad, std::acos(1.0 / std::sqrt(3.0)), kTol);
  EXPECT_NEAR(s.max_dihedral_rad, std::numbers::pi / 2, kTol);
  EXPECT_NEAR(s.min_edge, 1.0, kTol);
  EXPECT_NEAR(s.max_edge, std::sqrt(2.0), kTol);
  EXPECT_NEAR(s.circumradius, std::sqrt(3.0) / 2, kTol);
  for (const double c : s.circumcenter) EXPECT_NEAR(c, 0.5, kTol);
}

TEST(MeshQuality, OrientationDoesNotChangeShape) {
  const TetShape p = tet_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  const TetShape n = tet_shape({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1});
  EXPECT_NEAR(n.six_volume, -1.0, kTol);
  EXPECT_NEAR(n.radius_ratio, p.radius_ratio, kTol);
  EXPECT_NEAR(n.min_dihedral_rad, p.min_dihedral_rad, kTol);
  EXPECT_NEAR(n.circumradius, p.circumradius, kTol);
}

TEST(MeshQuality, FlatTetScoresZero) {
  const TetShape s = tet_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
  EXPECT_EQ(s.six_volume, 0.0);
  EXPECT_EQ(s.radius_ratio, 0.0);
}

TEST(MeshQuality, MeshSummary) {
  TetMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}};  // the second is inverted
  m.region_names = {"a", "b"};
  m.tet_region = {1, 1};
  m.surface_names = {"s", "t"};
  m.triangles = {{0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  m.triangle_surface = {1, 1, 0};
  const MeshQuality q = measure_quality(m);
  EXPECT_EQ(q.nodes, 5u);
  EXPECT_EQ(q.tets, 2u);
  EXPECT_EQ(q.triangles, 3u);
  EXPECT_EQ(q.inverted, 1u);
  EXPECT_NEAR(q.volume, 0.0, kTol);  // +1/6 - 1/6: signed, so inversions show
  EXPECT_NEAR(q.min_dihedral_deg, std::acos(1.0 / std::sqrt(3.0)) * kDeg, 1e-11);
  EXPECT_NEAR(q.max_dihedral_deg, 90.0, 1e-11);
  EXPECT_NEAR(q.worst_radius_ratio, std::sqrt(3.0) - 1.0, kTol);
  EXPECT_NEAR(q.mean_radius_ratio, std::sqrt(3.0) - 1.0, kTol);
  EXPECT_NEAR(q.min_edge, 1.0, kTol);
  EXPECT_NEAR(q.max_edge, std::sqrt(2.0), kTol);
  EXPECT_EQ(q.region_tets, (std::vector<std::pair<std::string, size_t>>{{"a", 0}, {"b", 2}}));
  EXPECT_EQ(q.surface_triangles, (std::vector<std::pair<std::string, size_t>>{{"s", 1}, {"t", 2}}));

  const nlohmann::json j = quality_to_json(q);
  EXPECT_EQ(j["tets"], 2);
  EXPECT_EQ(j["inverted"], 1);
  EXPECT_EQ(j["surface_triangles"]["t"], 2);
  EXPECT_EQ(j["region_tets"]["b"], 2);

  const std::string text = format_quality(q);
  EXPECT_NE(text.find("2 tets"), std::string::npos) << text;
  EXPECT_NE(text.find("inverted tets 1"), std::string::npos) << text;
  EXPECT_NE(text.find("b (2 tets)"), std::string::npos) << text;
}

}  // namespace
}  // namespace rift
