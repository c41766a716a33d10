#pragma once
// The FEMDEM solid mesh: inside a fracture zone every tet owns its 4 nodes and a 6-node joint ties each
// pair of tets across an interior face; outside the zone tets keep shared nodes and no joints exist
// (model only what the scene requires). A face between a zone tet and an outside tet carries a joint too,
// since the zone tet's copy of the face is its own.
//
// Joint corners (kernels/joint_forces.hpp): 0-2 are tet A's face in reversed outward order, 3-5 the
// copies in tet B of the same mesh vertices, so the mid-surface normal points from B into A and a
// positive opening means separation. Tet A is the lower tet index of the pair.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/mesh/tet_mesh.hpp"

namespace rift {

struct DiscontinuousMesh {
  std::vector<std::array<double, 3>> nodes;         // solid nodes (copies share coordinates)
  std::vector<int32_t> node_vertex;                 // the input mesh vertex each solid node copies
  std::vector<std::array<int32_t, 4>> tets;         // same order as the input tets, solid node ids
  std::vector<uint8_t> tet_in_zone;                 // 1 when the tet has private nodes
  std::vector<std::array<int32_t, 6>> joints;       // corners as above
  std::vector<std::array<int32_t, 2>> joint_tets;   // (tet A, tet B)
  std::vector<std::array<int32_t, 2>> joint_faces;  // local face index (opposite corner) in A and in B
  std::vector<std::array<int32_t, 3>> triangles;    // the input's surface triangles on solid node ids
};

// in_zone(tet index) tells which tets get private nodes. Boundary triangles of the input are mapped to
// the copies of the one tet they bound; a triangle that bounds no tet is an error (rift::Error).
DiscontinuousMesh make_discontinuous(const TetMesh& mesh, const std::function<bool(size_t)>& in_zone);

}  // namespace rift
