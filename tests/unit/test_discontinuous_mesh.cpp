// The FEMDEM mesh: private nodes and joints inside the fracture zone, shared nodes outside.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "engine/mesh/discontinuous_mesh.hpp"

using namespace rift;

namespace {

// A unit cube as 6 Kuhn tets around the main diagonal (0,0,0)-(1,1,1), all positively oriented, with
// its 12 boundary triangles on surface "boundary". Interior faces: 6 (each tet shares 2 faces).
TetMesh kuhn_cube() {
  TetMesh m;
  for (int i = 0; i < 8; ++i) m.nodes.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  const int paths[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (const auto& p : paths) {
    std::array<int32_t, 4> t{0, p[0], p[0] + p[1], 7};
    auto& a = m.nodes;
    auto sub = [&](int i, int j, int c) { return a[t[i]][c] - a[t[j]][c]; };
    const double det = sub(1, 0, 0) * (sub(2, 0, 1) * sub(3, 0, 2) - sub(2, 0, 2) * sub(3, 0, 1)) -
                       sub(1, 0, 1) * (sub(2, 0, 0) * sub(3, 0, 2) - sub(2, 0, 2) * sub(3, 0, 0)) +
                       sub(1, 0, 2) * (sub(2, 0, 0) * sub(3, 0, 1) - sub(2, 0, 1) * sub(3, 0, 0));
    if (det < 0) std::swap(t[1], t[2]);
    m.tets.push_back(t);
    m.tet_region.push_back(0);
  }
  m.region_names = {"domain"};
  m.surface_names = {"boundary"};
  // Boundary faces: those whose 3 vertices share a coordinate at 0 or 1.
  const int faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (const auto& t : m.tets)
    for (const auto& f : faces)
      for (int c = 0; c < 3; ++c) {
        const double v = m.nodes[t[f[0]]][c];
        if ((v == 0 || v == 1) && m.nodes[t[f[1]]][c] == v && m.nodes[t[f[2]]][c] == v) {
          m.triangles.push_back({t[f[0]], t[f[1]], t[f[2]]});
          m.triangle_surface.push_back(0);
        }
      }
  return m;
}

std::array<double, 3> centroid(const DiscontinuousMesh& d, int32_t tet) {
  std::array<double, 3> c{};
  for (int32_t n : d.tets[tet])
    for (int i = 0; i < 3; ++i) c[i] += 0.25 * d.nodes[n][i];
  return c;
}

}  // namespace

TEST(DiscontinuousMesh, WholeZoneGivesPrivateNodesAndOneJointPerInteriorFace) {
  const TetMesh m = kuhn_cube();
  ASSERT_EQ(m.triangles.size(), 12u);
  const DiscontinuousMesh d = make_discontinuous(m, [](size_t) { return true; });
  EXPECT_EQ(d.nodes.size(), 24u);  // 4 per tet
  EXPECT_EQ(d.joints.size(), 6u);  // (4 x 6 - 12) / 2 interior faces
  for (size_t j = 0; j < d.joints.size(); ++j) {
    const auto& J = d.joints[j];
    for (int i = 0; i < 3; ++i) {
      EXPECT_NE(J[i], J[i + 3]);
      EXPECT_EQ(d.node_vertex[J[i]], d.node_vertex[J[i + 3]]);  // facing corners copy one vertex
      EXPECT_EQ(d.nodes[J[i]], d.nodes[J[i + 3]]);
    }
    // The mid-surface normal points from tet B into tet A (positive opening = separation).
    const auto& x0 = d.nodes[J[0]];
    const auto& x1 = d.nodes[J[1]];
    const auto& x2 = d.nodes[J[2]];
    const double a[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
    const double b[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
    const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    const auto ca = centroid(d, d.joint_tets[j][0]);
    const auto cb = centroid(d, d.joint_tets[j][1]);
    EXPECT_GT(n[0] * (ca[0] - cb[0]) + n[1] * (ca[1] - cb[1]) + n[2] * (ca[2] - cb[2]), 0.0) << "joint " << j;
    EXPECT_LT(d.joint_tets[j][0], d.joint_tets[j][1]);
  }
  // Boundary triangles land on the copies of their own tet, at the same coordinates.
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(d.nodes[d.triangles[t][i]], m.nodes[m.triangles[t][i]]);
}

TEST(DiscontinuousMesh, EmptyZoneKeepsTheContinuousMesh) {
  const TetMesh m = kuhn_cube();
  const DiscontinuousMesh d = make_discontinuous(m, [](size_t) { return false; });
  EXPECT_EQ(d.nodes.size(), 8u);
  EXPECT_TRUE(d.joints.empty());
  for (size_t e = 0; e < m.tets.size(); ++e) EXPECT_EQ(d.tets[e], m.tets[e]);
}

TEST(DiscontinuousMesh, PartialZoneJointsOnlyWhereAZoneTetTakesPart) {
  const TetMesh m = kuhn_cube();
  // Tets 0 and 1 in the zone: each has 2 interior faces; they share none or one with each other.
  const DiscontinuousMesh d = make_discontinuous(m, [](size_t e) { return e < 2; });
  size_t expected = 0;
  const DiscontinuousMesh all = make_discontinuous(m, [](size_t) { return true; });
  for (const auto& jt : all.joint_tets) expected += (jt[0] < 2 || jt[1] < 2) ? 1 : 0;
  EXPECT_EQ(d.joints.size(), expected);
  EXPECT_GT(expected, 0u);
  // Shared nodes: the vertices of tets 2..5; private: 8.
  std::vector<bool> used(8, false);
  for (size_t e = 2; e < 6; ++e)
    for (int32_t v : m.tets[e]) used[v] = true;
  EXPECT_EQ(d.nodes.size(), size_t(std::count(used.begin(), used.end(), true)) + 8);
}

TEST(DiscontinuousMesh, TriangleInsideTheMeshIsRejected) {
  TetMesh m = kuhn_cube();
  m.triangles.push_back({0, m.tets[0][1], 7});  // an interior face (contains the diagonal)
  m.triangle_surface.push_back(0);
  EXPECT_THROW(make_discontinuous(m, [](size_t) { return true; }), Error);
}
