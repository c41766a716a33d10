#pragma once
// Tet mesh of a disc for the Brazilian (indirect tensile) test: diameter D, thickness t, axis along z
// through (origin.x, origin.y), flat faces at z = origin.z and origin.z + t. Generated with CGAL Mesh_3
// through polyhedral_mesher.hpp (which states how sizes are enforced, determinism, output layout).
//
// Geometry. The curved side is given to Mesh_3 as a polygon inscribed in the circle, extruded over t,
// with a vertex at each end of the two loading arcs (angles 90 +- a/2 and -90 +- a/2 deg, a =
// load_arc); each of the four arcs between those vertices is split into equal facets with chords of at
// most size_min / 4 and angles of at most 5 deg. The side is handed over as four surface patches
// (load_top, side right, load_bottom, side left) plus the two flat faces. Only patch borders (the four
// arc-end lines and the two rims) are protected edges: the facet edges inside a patch are not, so the
// mesh's side triangles span several facets, like any tet mesh of a curved surface.
//   Why not protect every facet edge, which would make volumes and areas exactly the prism's? Tried
// first, with chords of 1 to 3 h: Mesh_3 aborted on 2 or 3 of 24 random disc specs ("A facet is not in
// conflict with its refinement point", on nodes rounded off a slanted facet plane), left tets of zero
// volume (chords of h), and made 30 - 50 % more tets. Box faces are axis-aligned and not affected.
//   Consequence: every boundary node lies on the polygon prism (exactly on the flat faces), the mesh is
// inscribed in it, and no triangle crosses an arc end or a rim (patch borders are mesh edges). The
// volume falls short of the circle's pi D^2 t / 4 by the chord error of the side triangles, ~ h^2:
// -0.19 % at h = 2.5 mm and -0.074 % at h = 1.5 mm on a 50 x 25 mm disc. The polygon alone is within
// (size_min / 4)^2 / (8 R) of the circle.
//
// Sizing: h(p) = min(size_max, size_min + grading * d(p)), d = distance to the nearest loading arc
// (the circular arc, over the thickness; same rule as the box's notches); size_min = size_max gives a
// uniform mesh.
//
// Surfaces: load_top (the side within +-a/2 of the +y direction), load_bottom (the same around -y),
// side (the rest of the curved side), zmin, zmax (the flat faces). Region "domain".
#include <array>
#include <vector>

#include "engine/core/vec3.hpp"
#include "engine/mesh/polyhedral_mesher.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

struct DiscShape {
  std::array<double, 2> centre{};  // axis (x, y) [m]
  double radius = 0.0, z0 = 0.0, z1 = 0.0;
  double half_arc = 0.0;  // half the loading arc [rad]
  int load_facets = 0;    // facets per loading arc
  int side_facets = 0;    // facets per side arc (between the loading arcs)
  // Counterclockwise from the end of load_bottom at angle -90 + a/2: side (right), load_top, side
  // (left), load_bottom; 2 * (load_facets + side_facets) vertices.
  std::vector<std::array<double, 2>> polygon;
};

// Validates `spec` (a cylinder) and builds the outline. Throws rift::Error naming the offending field
// ("mesh.generate.cylinder.load_arc: expected ..., found ...").
DiscShape make_disc(const MeshGenerateSpec& spec);

// Distance from p to the nearest loading arc (the circular arcs of load_top and load_bottom, extruded
// over the thickness) [m].
double distance_to_load_arcs(const DiscShape& disc, const Vec3& p);

// Target element size h(p) (see above).
double disc_mesh_size_at(const MeshGenerateSpec& spec, const DiscShape& disc, const Vec3& p);

// The polygon's area [m^2].
double disc_polygon_area(const DiscShape& disc);

// Throws rift::Error for an invalid spec (see make_disc) or if meshing fails.
TetMesh generate_cylinder_mesh(const MeshGenerateSpec& spec, Mesh3Stats* stats = nullptr);

}  // namespace rift
