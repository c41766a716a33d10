#pragma once
// Tet mesh of a closed polyhedral solid with CGAL Mesh_3: Delaunay refinement of a polyhedral complex
// domain (CGAL::Polyhedral_complex_mesh_domain_3) whose protected edges are the borders between the
// given surface patches plus, inside each patch, the edges where the normal turns by more than
// feature_angle_deg. Protected edges and the planar faces between them are reproduced exactly; a
// patch made of slightly turning facets (a faceted curve, edges not protected) is meshed like a
// curved surface, its nodes on the facets and its triangles spanning them. No triangle crosses a
// protected edge. The generators (box_generator, cylinder_generator) describe their shape, sizing
// field and surface names; this file is the only one that sees CGAL.
//
// Sizing h(p), given by the caller, is used by Mesh_3 as
//   edge_size   - distance between consecutive points on protected edges,
//   facet_size  - radius of the surface Delaunay ball of every boundary triangle,
//   cell_size   - circumradius of every tet (evaluated at its circumcentre),
// so edges are at most 2 h (a chord of a circle or sphere of radius <= h); a tet's longest edge is
// typically 1.4 h. Mesh_3 does not enforce this inside the protecting balls of sharp edges, and sliver
// removal moves vertices without re-checking it: on the notched blocks tried, 0.4 - 1.9 % of tets
// exceeded the circumradius bound, by up to 26 %.
// Also: facet_angle 25 deg, facet_distance 0.1 h (irrelevant on planar faces), cell_radius_edge_ratio
// 3, facet vertices on one surface patch (no triangle bends over a sharp edge), then sliver perturbation
// (bound 10 deg) and exudation (bound 20 deg), with no time limits.
//
// Determinism: the same input (seed included) gives the same arrays, bit for bit. Mesh_3 runs
// sequentially, its random generators (the domain's and CGAL's default one) are seeded from `seed`,
// and the optimisation steps run without the time limits that would make them depend on machine speed.
// Those generators alone left the mesh unchanged (the refinement is seeded by the protected edges, not
// by random points), so a seed other than 1 also lowers h(p) by a seeded smooth factor in [0.9, 1]
// (polyhedral_mesher.cpp, SizeJitter): another mesh of the same sizing contract, for mesh-dependence
// studies. Seed 1 is the unjittered mesh.
//
// Output: nodes, positively oriented tets (region "domain"), boundary triangles with outward normals,
// grouped by the surface the caller's classifier assigns (stable order within a surface).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/core/vec3.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace rift {

// A surface (closed, or one patch of a closed surface) given as planar polygons with outward
// (counterclockwise seen from outside) vertex order; polygons need not be convex.
struct PolyhedralSurface {
  std::vector<Vec3> points;
  std::vector<std::vector<size_t>> faces;
};

// The prism over a counterclockwise polygon in (s, t), extruded over w in [w0, w1]; to_3d maps
// (s, t, w) to space and must keep orientation (s, t, w right-handed) so the faces face outward.
PolyhedralSurface extruded_polygon(const std::vector<std::array<double, 2>>& polygon, double w0, double w1,
                                   const std::function<Vec3(double s, double t, double w)>& to_3d);

struct PolyhedralMeshInput {
  std::vector<PolyhedralSurface> patches;  // together a closed surface; their borders are protected
  // Edges inside a patch where the surface normal turns by more than this are protected too. It must
  // lie between round-off (coplanar triangles of one face) and the smallest turn to be kept sharp.
  double feature_angle_deg = 1.0;
  std::function<double(const Vec3&)> size;  // h(p) [m], see above
  uint32_t seed = 1;
  // Meshing is refused, before it starts, when element_estimate.hpp expects more tets than this; the
  // message names max_tets_key as the key that raises it. 0: no bound.
  uint64_t max_tets = 0;
  std::string max_tets_key;
  std::vector<std::string> surface_names;
  // Index into surface_names of a boundary triangle (outward, nodes of `mesh`).
  std::function<int32_t(const TetMesh& mesh, const std::array<int32_t, 3>& triangle)> classify;
};

// Wall-clock cost of the stages, for the log.
struct Mesh3Stats {
  double refine_seconds = 0.0, perturb_seconds = 0.0, exude_seconds = 0.0;
  bool exude_capped = false;    // exudation hit its step cap (see polyhedral_mesher.cpp)
  double estimated_tets = 0.0;  // the estimate checked against max_tets (0 without a bound)
};

// Throws rift::Error if the estimate passes max_tets or meshing produces no tets.
TetMesh mesh_polyhedron(const PolyhedralMeshInput& input, Mesh3Stats* stats = nullptr);

}  // namespace rift
