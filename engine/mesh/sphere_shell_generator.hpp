#pragma once
// Tet mesh of a quarter of the spherical shell R <= |x| <= b (y >= 0, z >= 0), centred at the origin,
// for Stokes flow past a sphere with the symmetry planes y = 0 and z = 0 (flow along x). Generated with
// CGAL Mesh_3 through polyhedral_mesher.hpp (which states how sizes are enforced, determinism and the
// output layout).
//
// Geometry. Both spheres are given as latitude-longitude facets about the x axis (polar angle a in
// [0, pi] from +x, azimuth c in [0, pi/2] from +y towards +z), at most 3 deg and chords of at most
// h / 4 of the local size; the two planar faces are half annuli whose arcs are the same points. Only
// the patch borders (the four half circles) are protected edges, so the spheres are meshed as curved
// surfaces (nodes on the facets, triangles spanning several). The inner facets are within
// R (1 - cos(da / 2)) of the sphere (3.4e-4 R at 3 deg).
//
// Sizing: h(p) = min(size_max, size_min + grading (|p| - R)).
//
// Surfaces: sphere (|x| = R), outer (|x| = b), ymin (y = 0), zmin (z = 0). Region "domain".
#include "engine/mesh/polyhedral_mesher.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace rift {

struct SphereShellSpec {
  double radius = 1.0;        // R [m]
  double outer_radius = 5.0;  // b > R [m]
  double size_min = 0.1;      // h at the sphere [m]
  double size_max = 1.0;      // [m]
  double grading = 0.3;       // dh / dr
  uint32_t seed = 1;
};

// Throws rift::Error for an invalid spec or if meshing fails.
TetMesh generate_sphere_shell_mesh(const SphereShellSpec& spec, Mesh3Stats* stats = nullptr);

}  // namespace rift
