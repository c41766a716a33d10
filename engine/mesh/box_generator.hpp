#pragma once
// Tet mesh of a box minus notches, generated with CGAL Mesh_3 through polyhedral_mesher.hpp (which
// states how sizes are enforced, determinism, and the output layout).
//
// Sizing: h(p) = min(size_max, size_min + grading * d(p)), d = distance to the nearest notch face
// (mesh_size_at in notched_box.hpp); size_max everywhere without a notch.
//
// A narrow wedge is refined down to its gap width near the tip, whatever size_min says: Delaunay
// refinement must resolve the local feature size to keep the two notch faces apart. The paper's wedge
// (2.45 mm over 24.5 mm, 5.7 deg) at size_min 2 mm gets edges of 0.08 mm there, and 70 % of the
// boundary triangles on the notch. A slot of the same opening does not have this problem.
//
// Surfaces: xmin xmax ymin ymax zmin zmax (triangles in those planes) and each notch's name.
#include "engine/mesh/polyhedral_mesher.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

// Throws rift::Error for an invalid spec (see make_notched_box) or if meshing fails.
TetMesh generate_box_mesh(const MeshGenerateSpec& spec, Mesh3Stats* stats = nullptr);

}  // namespace rift
