#pragma once
// Which face of an axis-aligned box [lo, hi] a boundary triangle lies on: the face whose plane holds its
// three nodes. Mesh_3 puts nodes on the planes only to within its inexact constructions (seen: 4e-9 m
// off a face of a 0.1 m box meshed at 0.7 mm, 2e-7 of the face's extent), so a node counts as on a
// plane within kOnPlaneFraction of the triangle's longest edge: a triangle tilted by 0.06 degrees. The
// other surfaces a generator makes (notch faces, a disc's side) meet the box's planes at 5 degrees or
// more, so none of their triangles can pass. Faces are numbered xmin xmax ymin ymax zmin zmax (0 .. 5).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/mesh/tet_mesh.hpp"

namespace rift {

inline constexpr double kOnPlaneFraction = 1e-3;

inline double longest_edge(const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
  double longest = 0;
  for (int e = 0; e < 3; ++e) {
    const auto& a = mesh.nodes[tri[e]];
    const auto& b = mesh.nodes[tri[(e + 1) % 3]];
    longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
  }
  return longest;
}

// The largest distance of the triangle's nodes from the plane x[axis] = value.
inline double distance_from_plane(const TetMesh& mesh, const std::array<int32_t, 3>& tri, int axis,
                                  double value) {
  double worst = 0;
  for (const int32_t v : tri) worst = std::max(worst, std::abs(mesh.nodes[v][axis] - value));
  return worst;
}

// -1 when the triangle lies on no face.
inline int32_t box_face_of(const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                           const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
  const double tol = kOnPlaneFraction * longest_edge(mesh, tri);
  int32_t best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const double d = distance_from_plane(mesh, tri, a, side ? hi[a] : lo[a]);
      if (d <= tol && d < best_distance) best = 2 * a + side, best_distance = d;
    }
  return best;
}

}  // namespace rift
