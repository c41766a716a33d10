#pragma once
// The shape the box generator meshes, without any CGAL: a box minus notches that run through it along
// one axis is a prism, i.e. a 2-D polygon (the cross-section) extruded along that "through" axis.
// Cross-section coordinates (s, t) are the two other axes in cyclic order (through z: s = x, t = y;
// through x: s = y, t = z; through y: s = z, t = x), so a counterclockwise polygon extruded along +w
// gives outward-facing side faces.
#include <array>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"

namespace rift {

struct NotchedBox {
  std::array<int, 3> axis{0, 1, 2};            // axis[0] = s, axis[1] = t, axis[2] = w (through axis)
  std::array<double, 3> lo{}, hi{};            // box corners
  std::vector<std::array<double, 2>> polygon;  // cross-section, counterclockwise in (s, t)
  std::vector<int> edge_notch;                 // per polygon edge i -> i+1: notch index, or -1 for a box face
  std::vector<std::string> surface_names;      // xmin xmax ymin ymax zmin zmax, then notch names
  std::vector<int> notch_surface;              // per notch: index into surface_names
};

// Validates `spec` and builds the cross-section. Throws rift::Error naming the offending field
// ("mesh.generate.notches[0].depth: expected ..., found ...") for anything that does not make a valid
// simple prism: bad sizes, a notch wider than its face, deeper than the box, overlapping another notch,
// notches along different through axes, or meeting its face at less than 5 degrees.
NotchedBox make_notched_box(const MeshGenerateSpec& spec);

// 3-D point from cross-section coordinates and the through coordinate.
std::array<double, 3> to_3d(const NotchedBox& box, double s, double t, double w);

// Distance from `p` to the nearest face of notch `notch` (its polygon edges extruded over the box's
// through extent), or of any notch with notch = -1; +infinity when there is none.
double distance_to_notches(const NotchedBox& box, const std::array<double, 3>& p, int notch = -1);

// Target element size h(p) = min(size_max, size_min + grading * d(p)), d = distance_to_notches;
// size_max everywhere without a notch. Mesh_3 bounds circumradii by it (see box_generator.hpp).
double mesh_size_at(const MeshGenerateSpec& spec, const NotchedBox& box, const std::array<double, 3>& p);

}  // namespace rift
