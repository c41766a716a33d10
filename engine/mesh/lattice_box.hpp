#pragma once
// A box cut into n_x x n_y x n_z cubes, each split into the 6 tets of Kuhn's (Freudenthal's)
// triangulation: all six share the cube's main diagonal (0,0,0)-(1,1,1) and follow the monotone paths
// from one end to the other, one per ordering of the axes. The split is the same in every cube, so the
// faces match across cubes and every plane x = i h_x (likewise y, z) is a union of tet faces.
//
// Used where exact planes matter more than element shape: cracks along a lattice plane in the mesh
// conversion tests, meshes of 1e4-1e6 tets in benchmarks (instant, unlike Mesh_3), convergence studies.
// Tets are positively oriented; nodes are numbered x fastest, then y, then z.
//
// Surfaces: xmin xmax ymin ymax zmin zmax (two triangles per boundary cube face); one region "domain".
#include <array>

#include "engine/mesh/tet_mesh.hpp"

namespace rift {

// Throws rift::Error when a count is below 1 or a size is not positive.
TetMesh generate_lattice_box(std::array<int, 3> cells, std::array<double, 3> size);

}  // namespace rift
