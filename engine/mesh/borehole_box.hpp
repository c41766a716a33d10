#pragma once
// A box [lo, hi] with a cylindrical hole (a borehole) along z, meshed as an O-grid Kuhn lattice graded
// towards the hole: the Kuhn lattice of lattice_box.hpp with its radial index running from the hole's
// wall out to the box's sides, its hoop index around the axis and its third index along z. For hydraulic
// fracturing from a well, where the stress concentration at the wall sets where a crack starts: cells of
// `size` at the wall, growing by `growth` per ring outward, a few thousand tets for what a uniform
// lattice would need millions for, and no Mesh_3 (instant, deterministic, exact planes).
//
// The axis (ax, ay) may lie inside the xy rectangle (the full hole), on one of its sides (a half model,
// the side is a symmetry plane) or on a corner (a quarter model); on the side(s) it does not sit on it
// must be at least 2 radii away. Angles theta are measured from +x, counter-clockwise. Hoop break points
// are the range's ends, the directions of the rectangle's corners (so every outer cell lies on one side
// and corners are nodes) and the axis directions 0, 90, 180, 270 degrees (so the planes y = ay and
// x = ax are lattice planes: a crack plane through the axis). Each segment between break points is cut
// into round(angle * radius / size) equal angles (at least one).
//
// Rays: along theta, R(theta) is the distance from the axis to the rectangle's boundary; ring k of N is
// at r = radius + (R - radius) s_k, s_k = (g^k - 1) / (g^N - 1) (k / N for g = 1), N chosen so that the
// first ring on the shortest ray is about `size` thick. The wall (ring 0) is a polygon inscribed in the
// circle (its nodes are on it, its faces are chords); the last ring is exactly on the box's sides.
// Layers along z: round((hi.z - lo.z) / size) uniform ones. The map from the lattice is orientation
// preserving (radial out, hoop counter-clockwise, z up), so every tet is positive (checked on build).
// For the full hole the seam at theta = 0 is shared: the mesh is conforming all round.
//
// Surfaces: xmin xmax ymin ymax zmin zmax borehole (a side with no triangles keeps its name); one region
// "domain". Node order: radial fastest, then hoop, then z (the lattice's, the full hole's seam copy
// removed).
#include <array>
#include <cstddef>
#include <cstdint>

#include "engine/mesh/tet_mesh.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

struct BoreholeBoxSpec {
  std::array<double, 3> lo{}, hi{};  // the box
  std::array<double, 2> axis{};      // x, y of the hole's axis
  double radius = 0;                 // hole radius [m]
  double size = 0;                   // cell size at the wall [m]
  double growth = 1;                 // ratio of neighbouring rings' radial sizes, in [1, 2]
};

struct BoreholeLatticeCounts {
  size_t hoop = 0, rings = 0, layers = 0;
  uint64_t tets() const { return 6ull * hoop * rings * layers; }
};

// The lattice's cell counts without building it (for budgets); the built mesh has counts.tets() tets.
// Throws rift::Error when the spec is invalid.
BoreholeLatticeCounts borehole_box_counts(const BoreholeBoxSpec& spec);

// Throws rift::Error when the spec is invalid (the message names the field or side and the value).
TetMesh borehole_box(const BoreholeBoxSpec& spec);

// The scene's mesh.generate: a box [origin, origin + extent] with its borehole section.
BoreholeBoxSpec borehole_box_spec(const std::array<double, 3>& origin, const std::array<double, 3>& extent,
                                  const BoreholeMeshSpec& hole);

}  // namespace rift
