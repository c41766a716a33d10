#pragma once
// Renumbers a mesh along a space-filling (Morton, Z-order) curve: vertices by position, tets by centroid,
// so that elements close in space are close in memory. The solid's private nodes follow the tet order and
// its joints the order in which their second tet is met, so after this the node pass gathers its tet and
// joint corners from nearby rows instead of from all over the tables (docs/performance.md: the jointed step
// at 1e5 tets ran at half its 1e4-tet speed per tet before, from cache misses).
//
// Deterministic: ties in the 63-bit key are broken by the old index. Triangles keep their order (their
// vertex ids are renumbered); regions and surfaces are unchanged.
#include "engine/mesh/tet_mesh.hpp"

namespace rift {

void order_along_curve(TetMesh& mesh);

}  // namespace rift
