#pragma once
// Tet mesh of a box minus notches, generated with CGAL Mesh_3 (Delaunay refinement of a polyhedral
// domain whose sharp edges are protected, so box and notch edges and planar faces are reproduced).
//
// Sizing: h(p) = min(size_max, size_min + grading * d(p)), d = distance to the nearest notch face
// (mesh_size_at in notched_box.hpp). Mesh_3 uses h as
//   edge_size   - distance between consecutive points on protected edges,
//   facet_size  - radius of the surface Delaunay ball of every boundary triangle,
//   cell_size   - circumradius of every tet (evaluated at its circumcentre),
// so edges are at most 2 h (a chord of a circle or sphere of radius <= h); a tet's longest edge is
// typically 1.4 h. Mesh_3 does not enforce this inside the protecting balls of sharp edges, and sliver
// removal moves vertices without re-checking it: on the notched blocks tried, 0.4 - 1.9 % of tets
// exceeded the circumradius bound, by up to 26 %.
// Also: facet_angle 25 deg, facet_distance 0.1 h (irrelevant on planar faces), cell_radius_edge_ratio
// 3, facet vertices on one surface patch (no triangle bends over an edge), then sliver perturbation
// (bound 10 deg) and exudation (bound 20 deg), with no time limits.
//
// A narrow wedge is refined down to its gap width near the tip, whatever size_min says: Delaunay
// refinement must resolve the local feature size to keep the two notch faces apart. The paper's wedge
// (2.45 mm over 24.5 mm, 5.7 deg) at size_min 2 mm gets edges of 0.08 mm there, and 70 % of the
// boundary triangles on the notch. A slot of the same opening does not have this problem.
//
// Determinism: the same spec (seed included) gives the same arrays, bit for bit. Mesh_3 runs
// sequentially, its random generators (the domain's and CGAL's default one) are seeded from spec.seed,
// and the optimisation steps run without the time limits that would make them depend on machine speed.
//
// Output: nodes, positively oriented tets (region "domain"), boundary triangles with outward normals,
// grouped by surface: xmin xmax ymin ymax zmin zmax (triangles in those planes) and each notch's name.
#include "engine/mesh/tet_mesh.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

// Wall-clock cost of the stages, for the log.
struct BoxMeshStats {
  double refine_seconds = 0.0, perturb_seconds = 0.0, exude_seconds = 0.0;
  bool exude_capped = false;  // exudation hit its step cap (see box_generator.cpp)
};

// Throws rift::Error for an invalid spec (see make_notched_box) or if meshing fails.
TetMesh generate_box_mesh(const MeshGenerateSpec& spec, BoxMeshStats* stats = nullptr);

}  // namespace rift
