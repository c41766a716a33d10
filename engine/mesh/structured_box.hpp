#pragma once
// A structured tetrahedral mesh of an axis-aligned box, for verification and convergence studies (the Kuhn
// lattice of lattice_box.hpp, placed at [lo, hi]): the box
// [lo, hi] is cut into nx x ny x nz cells, each split into 6 tetrahedra along its main diagonal (Kuhn
// split: the 6 monotone paths from corner (0,0,0) to corner (1,1,1)). The split is translation invariant,
// so neighbouring cells share faces and the mesh is conforming. All tets are positively oriented.
// Named surfaces: "xmin", "xmax", "ymin", "ymax", "zmin", "zmax" (boundary triangles, 2 per cell face);
// one region "domain". Node (i, j, k) has index i + (nx + 1) * (j + (ny + 1) * k).
#include <array>
#include <vector>

#include "engine/mesh/tet_mesh.hpp"

namespace rift {

struct StructuredBoxSpec {
  std::array<double, 3> lo{0.0, 0.0, 0.0};
  std::array<double, 3> hi{1.0, 1.0, 1.0};
  std::array<int, 3> cells{4, 4, 4};  // nx, ny, nz >= 1
};

TetMesh structured_box(const StructuredBoxSpec& spec);

// The same lattice with its nodes at the given coordinates along each axis (each increasing, at least 2):
// a graded lattice (graded_axis.hpp). A map increasing along each axis keeps every tet positive.
TetMesh structured_box_on_axes(const std::array<std::vector<double>, 3>& coordinates);

}  // namespace rift
