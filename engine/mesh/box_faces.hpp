#pragma once
// Which face of an axis-aligned box [lo, hi] a boundary triangle lies on: the face whose plane holds its
// three nodes (Mesh_3 puts box-plane coordinates on the planes exactly; the tolerance, 1e-9 of the box's
// largest extent, only guards round-off). Faces are numbered xmin xmax ymin ymax zmin zmax (0 .. 5).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "engine/mesh/tet_mesh.hpp"

namespace rift {

// -1 when the triangle lies on no face.
inline int32_t box_face_of(const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                           const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
  const double tol = 1e-9 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const double plane = side ? hi[a] : lo[a];
      bool in_plane = true;
      for (const int32_t v : tri) in_plane = in_plane && std::abs(mesh.nodes[v][a] - plane) <= tol;
      if (in_plane) return 2 * a + side;
    }
  return -1;
}

}  // namespace rift
