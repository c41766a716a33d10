// Disc generator on CGAL Mesh_3 through polyhedral_mesher (see cylinder_generator.hpp for the contract).
#include "engine/mesh/cylinder_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "engine/core/error.hpp"
#include "engine/mesh/box_faces.hpp"

namespace rift {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
// Outline facets: chords of at most size_min / kChordDivisor and angles of at most kMaxFacetAngle.
// The chord keeps the polygon's sagitta (c^2 / 8R) a sixteenth of that of mesh edges of size_min;
// the angle keeps facet turns far below kPatchFeatureAngleDeg on coarse meshes.
constexpr double kChordDivisor = 4.0;
constexpr double kMaxFacetAngle = 5.0 * kDeg;
// Edges inside a patch turn by at most 5 deg, rims by 90: anything in between separates them.
constexpr double kPatchFeatureAngleDeg = 30.0;
// A bound on the outline's size, far beyond any mesh that could be built on it.
constexpr int kMaxFacets = 100000;

enum Surface : int32_t { kLoadTop, kLoadBottom, kSide, kZmin, kZmax };

[[noreturn]] void fail(const std::string& field, const std::string& expected, double found) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", found);
  throw Error("mesh.generate." + field + ": expected " + expected + ", found " + buffer);
}

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

void check_spec(const MeshGenerateSpec& spec) {
  const CylinderSpec& c = spec.cylinder;
  if (!(c.diameter > 0) || !std::isfinite(c.diameter))
    fail("cylinder.diameter", "a positive length", c.diameter);
  if (!(c.thickness > 0) || !std::isfinite(c.thickness))
    fail("cylinder.thickness", "a positive length", c.thickness);
  if (!(c.load_arc > 0 && c.load_arc < 90)) fail("cylinder.load_arc", "an angle in (0, 90) deg", c.load_arc);
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(spec.origin[k]))
      fail("origin[" + std::to_string(k) + "]", "a finite coordinate", spec.origin[k]);
  if (!(spec.size_min > 0) || !std::isfinite(spec.size_min))
    fail("size_min", "a positive length", spec.size_min);
  if (!(spec.size_max >= spec.size_min) || !std::isfinite(spec.size_max))
    fail("size_max", "a length >= size_min (" + num(spec.size_min) + ")", spec.size_max);
  if (!(spec.grading >= 0) || !std::isfinite(spec.grading)) fail("grading", "a number >= 0", spec.grading);
  // A loading arc shorter than one outline chord cannot be meshed at size_min: Mesh_3 protects its
  // ends with balls no larger than the arc and refines around them without bound (an arc of 1e-12 deg
  // ran for minutes).
  const double shortest = spec.size_min / kChordDivisor;
  const double arc = 0.5 * c.diameter * c.load_arc * kDeg;
  if (arc < shortest)
    throw Error(
        "mesh.generate.cylinder.load_arc: expected an angle whose arc on the rim is at least size_min / " +
        num(kChordDivisor) + " = " + num(shortest) +
        " m, the shortest edge the outline carries (>= " + num(shortest / (0.5 * c.diameter) / kDeg) +
        " deg), found " + num(c.load_arc) + " deg (an arc of " + num(arc) + " m)");
}

// The fewest equal facets over an arc of `span` rad with chords <= `chord` and angles <= kMaxFacetAngle.
int facets_for(double span, double chord, double radius) {
  const double max_angle = std::min(kMaxFacetAngle, 2 * std::asin(std::min(1.0, chord / (2 * radius))));
  const double n = std::max(1.0, std::ceil(span / max_angle));
  if (n > kMaxFacets)
    fail("size_min",
         "a length >= " + num(kChordDivisor * 2 * radius * std::sin(kPi / kMaxFacets)) +
             " (the outline would need more than 100000 facets)",
         chord * kChordDivisor);
  return static_cast<int>(n);
}

// Which named surface a boundary triangle lies on: a flat face when all three nodes are in its plane
// (to within Mesh_3's inexact constructions, see box_faces.hpp; the side meets the flat faces at 90
// degrees), otherwise the curved side, split by the angle of the centroid. A triangle's nodes are on one
// patch and patches meet at the arc ends, so the centroid's angle is strictly inside one patch's range:
// the test below is never borderline.
int32_t classify(const DiscShape& disc, const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
  const double tol = kOnPlaneFraction * longest_edge(mesh, tri);
  for (const auto& [z, surface] : {std::pair{disc.z0, kZmin}, std::pair{disc.z1, kZmax}})
    if (distance_from_plane(mesh, tri, 2, z) <= tol) return surface;
  double x = 0, y = 0;
  for (const int32_t v : tri) x += mesh.nodes[v][0] / 3, y += mesh.nodes[v][1] / 3;
  const double angle = std::atan2(y - disc.centre[1], x - disc.centre[0]);  // (-pi, pi]
  if (std::abs(angle - kPi / 2) < disc.half_arc) return kLoadTop;
  if (std::abs(angle + kPi / 2) < disc.half_arc) return kLoadBottom;
  return kSide;
}

}  // namespace

DiscShape make_disc(const MeshGenerateSpec& spec) {
  check_spec(spec);
  DiscShape d;
  d.centre = {spec.origin[0], spec.origin[1]};
  d.radius = 0.5 * spec.cylinder.diameter;
  d.z0 = spec.origin[2];
  d.z1 = spec.origin[2] + spec.cylinder.thickness;
  const double a = 0.5 * spec.cylinder.load_arc * kDeg;
  d.half_arc = a;
  d.load_facets = facets_for(2 * a, spec.size_min / kChordDivisor, d.radius);
  d.side_facets = facets_for(kPi - 2 * a, spec.size_min / kChordDivisor, d.radius);
  struct Arc {
    double start, span;
    int facets;
  };
  const Arc arcs[4] = {{-kPi / 2 + a, kPi - 2 * a, d.side_facets},
                       {kPi / 2 - a, 2 * a, d.load_facets},
                       {kPi / 2 + a, kPi - 2 * a, d.side_facets},
                       {3 * kPi / 2 - a, 2 * a, d.load_facets}};
  for (const Arc& arc : arcs)
    for (int k = 0; k < arc.facets; ++k) {
      const double angle = arc.start + arc.span * k / arc.facets;
      d.polygon.push_back(
          {d.centre[0] + d.radius * std::cos(angle), d.centre[1] + d.radius * std::sin(angle)});
    }
  return d;
}

double distance_to_load_arcs(const DiscShape& disc, const Vec3& p) {
  const double x = p[0] - disc.centre[0], y = p[1] - disc.centre[1];
  const double r = std::hypot(x, y), from_axis = std::abs(std::atan2(std::abs(x), std::abs(y)));
  // By symmetry only the top arc's half x >= 0 matters: angle from +y in [0, half_arc].
  double d2;
  if (from_axis <= disc.half_arc) {
    d2 = std::abs(r - disc.radius);
  } else {
    const double ex = disc.radius * std::sin(disc.half_arc), ey = disc.radius * std::cos(disc.half_arc);
    d2 = std::hypot(std::abs(x) - ex, std::abs(y) - ey);
  }
  const double dz = std::max({0.0, disc.z0 - p[2], p[2] - disc.z1});  // Mesh_3 may ask just outside
  return std::hypot(d2, dz);
}

double disc_mesh_size_at(const MeshGenerateSpec& spec, const DiscShape& disc, const Vec3& p) {
  if (spec.size_min >= spec.size_max) return spec.size_max;
  return std::min(spec.size_max, spec.size_min + spec.grading * distance_to_load_arcs(disc, p));
}

double disc_polygon_area(const DiscShape& disc) {
  const double load = disc.load_facets * std::sin(2 * disc.half_arc / disc.load_facets);
  const double side = disc.side_facets * std::sin((kPi - 2 * disc.half_arc) / disc.side_facets);
  return disc.radius * disc.radius * (load + side);  // 2 n triangles of area R^2 sin(theta) / 2 per arc pair
}

namespace {

// The side facets first .. first + count - 1 (edge i joins polygon vertices i and i + 1) as one patch.
PolyhedralSurface side_patch(const DiscShape& d, size_t first, size_t count) {
  PolyhedralSurface s;
  const size_t n = d.polygon.size();
  for (size_t k = 0; k <= count; ++k) {
    const auto& q = d.polygon[(first + k) % n];
    s.points.push_back({q[0], q[1], d.z0});
    s.points.push_back({q[0], q[1], d.z1});
  }
  for (size_t k = 0; k < count; ++k) s.faces.push_back({2 * k, 2 * k + 2, 2 * k + 3, 2 * k + 1});
  return s;
}

PolyhedralSurface cap_patch(const DiscShape& d, bool top) {
  PolyhedralSurface s;
  const size_t n = d.polygon.size();
  std::vector<size_t> face(n);
  for (size_t i = 0; i < n; ++i) {
    s.points.push_back({d.polygon[i][0], d.polygon[i][1], top ? d.z1 : d.z0});
    face[i] = top ? i : n - 1 - i;  // the bottom faces -z: reversed
  }
  s.faces.push_back(face);
  return s;
}

}  // namespace

TetMesh generate_cylinder_mesh(const MeshGenerateSpec& spec, Mesh3Stats* stats) {
  const DiscShape disc = make_disc(spec);
  const size_t load = static_cast<size_t>(disc.load_facets), side = static_cast<size_t>(disc.side_facets);
  PolyhedralMeshInput in;
  in.patches = {cap_patch(disc, false),
                cap_patch(disc, true),
                side_patch(disc, 0, side),
                side_patch(disc, side, load),
                side_patch(disc, side + load, side),
                side_patch(disc, 2 * side + load, load)};
  in.feature_angle_deg = kPatchFeatureAngleDeg;
  in.size = [&](const Vec3& p) { return disc_mesh_size_at(spec, disc, p); };
  in.seed = spec.seed;
  in.max_tets = spec.max_elements;
  in.max_tets_key = spec.max_elements_key;
  in.surface_names = {"load_top", "load_bottom", "side", "zmin", "zmax"};
  in.classify = [&](const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
    return classify(disc, mesh, tri);
  };
  return mesh_polyhedron(in, stats);
}

}  // namespace rift
