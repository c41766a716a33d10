// The adaptive fluid mesh's generator (engine/mesh/graded_box.hpp): exact box, sizes that follow the
// distance to a surface, determinism. Size tolerances as in test_box_generator.cpp (Mesh_3's contract).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/mesh/graded_box.hpp"
#include "engine/mesh/mesh_quality.hpp"
#include "engine/mesh/surface_distance.hpp"

namespace rift {
namespace {

// Two triangles: the square [0.3, 0.7]^2 in the plane z = 0.5 (a crack-like sheet inside the box).
std::vector<double> sheet() {
  return {0.3, 0.3, 0.5, 0.7, 0.3, 0.5, 0.7, 0.7, 0.5,  //
          0.3, 0.3, 0.5, 0.7, 0.7, 0.5, 0.3, 0.7, 0.5};
}

GradedBoxSpec unit_spec() {
  GradedBoxSpec s;
  s.lo = {0, 0, 0};
  s.hi = {1, 1, 1};
  s.size_min = 0.04;
  s.size_max = 0.25;
  s.grading = 0.4;
  return s;
}

TEST(SurfaceDistance, IsThePointToTriangleDistance) {
  const auto tris = sheet();
  const SurfaceDistance d(tris);
  EXPECT_EQ(d.triangle_count(), 2u);
  EXPECT_NEAR(d({0.5, 0.5, 0.8}), 0.3, 1e-15);                             // above the sheet
  EXPECT_NEAR(d({0.0, 0.5, 0.5}), 0.3, 1e-15);                             // beside an edge
  EXPECT_NEAR(d({0.0, 0.0, 0.5}), std::sqrt(0.18), 1e-15);                 // towards a corner
  EXPECT_EQ(SurfaceDistance(std::vector<double>{})({0, 0, 0}), HUGE_VAL);  // nothing to refine to
}

// The wedge scene's fluid box (its faces at coordinates no binary fraction holds) with a crack-like sheet
// inside: every vertex of a triangle on a face lies exactly on that face's plane, as a remesh needs (it
// finds each new node in the old mesh). The mesher alone leaves some 4e-10 m off the plane z = 0.0502.
TEST(GradedBox, TheBoundarysVerticesLieExactlyOnTheBoxsFaces) {
  GradedBoxSpec s;
  s.lo = {-0.005, -0.0002, -0.0002};
  s.hi = {-0.005 + 0.0542, -0.0002 + 0.1004, -0.0002 + 0.0504};
  s.size_min = 0.004;
  s.size_max = 0.008;
  s.grading = 0.3;
  std::vector<double> tris = sheet();
  for (size_t i = 0; i < tris.size(); ++i) tris[i] *= 0.05;
  const TetMesh m = generate_graded_box(s, tris);
  size_t off = 0;
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const size_t axis = static_cast<size_t>(m.triangle_surface[f] / 2);
    const double plane = m.triangle_surface[f] % 2 ? s.hi[axis] : s.lo[axis];
    for (const int32_t v : m.triangles[f]) off += m.nodes[static_cast<size_t>(v)][axis] != plane;
  }
  EXPECT_EQ(off, 0u);
}

TEST(GradedBox, IsTheBoxWithItsSixFaces) {
  const TetMesh m = generate_graded_box(unit_spec(), sheet());
  const MeshQuality q = measure_quality(m);
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_NEAR(q.volume, 1.0, 1e-12);
  ASSERT_EQ(m.surface_names.size(), 6u);
  for (const auto& [name, n] : q.surface_triangles) EXPECT_GT(n, 0u) << name;
  // Every face's triangles tile it: their areas sum to 1.
  std::vector<double> area(6, 0.0);
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const auto& t = m.triangles[f];
    double e1[3], e2[3];
    for (int d = 0; d < 3; ++d)
      e1[d] = m.nodes[t[1]][d] - m.nodes[t[0]][d], e2[d] = m.nodes[t[2]][d] - m.nodes[t[0]][d];
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    area[m.triangle_surface[f]] += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  for (int s = 0; s < 6; ++s) EXPECT_NEAR(area[s], 1.0, 1e-12) << m.surface_names[s];
}

// Mesh_3 bounds each tet's circumradius by h at its circumcentre, on all but a few per cent of tets
// (test_box_generator.cpp says why: sliver perturbation and exudation move vertices without re-checking
// sizes). Here 96.5 % meet it, a little below the notched blocks' 98-99.6 %: the steep grading towards a
// sheet inside the volume gives the optimisers more to move. So: 95 %, and every edge below 1.5 x 2h.
// Near the sheet the tets must be several times smaller than far away.
TEST(GradedBox, FollowsTheDistanceToTheSurface) {
  const GradedBoxSpec spec = unit_spec();
  const auto tris = sheet();
  const TetMesh m = generate_graded_box(spec, tris);
  const SurfaceDistance distance(tris);
  auto h = [&](const Vec3& p) { return std::min(spec.size_max, spec.size_min + spec.grading * distance(p)); };
  size_t meets = 0, near_n = 0, far_n = 0;
  double worst = 0, near_sum = 0, far_sum = 0;
  for (const auto& t : m.tets) {
    const TetShape s = tet_shape(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
    meets += s.circumradius <= h(s.circumcenter) * (1 + 1e-12);
    worst = std::max(worst, s.max_edge / (2 * h(s.circumcenter)));
    Vec3 c{0, 0, 0};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) c[d] += 0.25 * m.nodes[t[a]][d];
    if (distance(c) < spec.size_min) near_sum += s.max_edge, ++near_n;
    if (h(c) == spec.size_max) far_sum += s.max_edge, ++far_n;
  }
  EXPECT_GT(static_cast<double>(meets), 0.95 * static_cast<double>(m.tets.size()));
  EXPECT_LT(worst, 1.5);
  ASSERT_GT(near_n, 0u);
  ASSERT_GT(far_n, 0u);
  EXPECT_LT(near_sum / near_n, 0.4 * far_sum / far_n);  // h: 0.04 against 0.25
  std::printf(
      "graded box: %zu tets, %zu meet R <= h; worst edge %.3f x 2h; longest edge near %.4g, far %.4g\n",
      m.tets.size(), meets, worst, near_sum / near_n, far_sum / far_n);
}

TEST(GradedBox, SameInputGivesIdenticalMesh) {
  const TetMesh a = generate_graded_box(unit_spec(), sheet());
  const TetMesh b = generate_graded_box(unit_spec(), sheet());
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_surface, b.triangle_surface);
}

TEST(GradedBox, RejectsAnInvalidSpec) {
  GradedBoxSpec s = unit_spec();
  s.size_max = 0.01;  // below size_min
  EXPECT_THROW(generate_graded_box(s, sheet()), Error);
  s = unit_spec();
  s.hi[1] = 0.0;
  EXPECT_THROW(generate_graded_box(s, sheet()), Error);
}

}  // namespace
}  // namespace rift
