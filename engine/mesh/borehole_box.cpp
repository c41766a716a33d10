#include "engine/mesh/borehole_box.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/mesh/box_faces.hpp"
#include "engine/mesh/lattice_box.hpp"

namespace rift {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSameAngle = 1e-12;  // [rad]: break points closer than this are one
constexpr double kMaxCells = 1e7;     // along one lattice axis: far beyond any budget, short of overflow
enum Surface : int32_t { kXmin, kXmax, kYmin, kYmax, kZmin, kZmax, kBorehole };
constexpr const char* kSideNames[4] = {"xmin", "xmax", "ymin", "ymax"};

void check_sizes(const BoreholeBoxSpec& s) {
  for (int d = 0; d < 3; ++d)
    if (!(s.hi[d] > s.lo[d]))
      throw Error(fmt::format("borehole box: expected lo < hi along {}, found {:g} and {:g}", "xyz"[d],
                              s.lo[d], s.hi[d]));
  if (!(s.radius > 0))
    throw Error(fmt::format("borehole box: expected a positive radius, found {:g} m", s.radius));
  if (!(s.size > 0) || !(s.size <= s.radius))
    throw Error(
        fmt::format("borehole box: expected a size at the wall in (0, radius] = (0, {:g}] m, found {:g} m",
                    s.radius, s.size));
  if (!(s.growth >= 1 && s.growth <= 2))
    throw Error(fmt::format("borehole box: expected a growth in [1, 2], found {:g}", s.growth));
}

// The distances from the axis to the sides xmin xmax ymin ymax: 0 exactly for a side the axis sits on
// (x - y == 0 only when x == y), negative for one it is outside of.
std::array<double, 4> side_distances(const BoreholeBoxSpec& s) {
  return {s.axis[0] - s.lo[0], s.hi[0] - s.axis[0], s.axis[1] - s.lo[1], s.hi[1] - s.axis[1]};
}

// Closer than 2 radii the first ring would be squeezed between the wall and the side.
void check_axis(const BoreholeBoxSpec& s) {
  const std::array<double, 4> d = side_distances(s);
  if (!(d[0] >= 0 && d[1] >= 0 && d[2] >= 0 && d[3] >= 0))
    throw Error(fmt::format(
        "borehole box: expected the axis in the box's xy rectangle [{:g}, {:g}] x [{:g}, {:g}] (on a side or "
        "a corner for a half or quarter model), found ({:g}, {:g})",
        s.lo[0], s.hi[0], s.lo[1], s.hi[1], s.axis[0], s.axis[1]));
  for (int side = 0; side < 4; ++side)
    if (d[side] != 0 && d[side] < 2 * s.radius)
      throw Error(fmt::format(
          "borehole box: the borehole (radius {:g} m) must be at least 2 radii from every side it does not "
          "sit on: {} is {:g} m from the axis",
          s.radius, kSideNames[side], d[side]));
}

void check(const BoreholeBoxSpec& s) {
  check_sizes(s);
  check_axis(s);
  if (2 * kPi * s.radius / s.size > kMaxCells || (s.hi[2] - s.lo[2]) / s.size > kMaxCells)
    throw Error(fmt::format(
        "borehole box: a size of {:g} m makes more than 1e7 cells around the hole or along z", s.size));
}

// The angles the mesh covers: [start, start + span], the whole circle when the axis is inside.
struct AngularRange {
  double start = 0, span = 2 * kPi;
  bool full = true;
};

AngularRange angular_range(const BoreholeBoxSpec& s) {
  const std::array<double, 4> d = side_distances(s);
  const bool on_x = d[0] == 0 || d[1] == 0, on_y = d[2] == 0 || d[3] == 0;
  if (!on_x && !on_y) return {};
  if (!on_y) return {d[0] == 0 ? -kPi / 2 : kPi / 2, kPi, false};
  if (!on_x) return {d[2] == 0 ? 0.0 : kPi, kPi, false};
  const double start = d[0] == 0 ? (d[2] == 0 ? 0.0 : -kPi / 2) : (d[2] == 0 ? kPi / 2 : kPi);
  return {start, kPi / 2, false};
}

// Corners counter-clockwise from (lo.x, lo.y).
std::array<double, 2> corner_point(const BoreholeBoxSpec& s, int corner) {
  return {corner == 1 || corner == 2 ? s.hi[0] : s.lo[0], corner >= 2 ? s.hi[1] : s.lo[1]};
}

struct BreakPoint {
  double theta = 0;
  int corner = -1;  // the corner the ray ends at, or -1
};

void add_if_inside(const AngularRange& range, double theta, int corner, std::vector<BreakPoint>& points) {
  theta -= 2 * kPi * std::floor((theta - range.start) / (2 * kPi));  // into [start, start + 2 pi)
  if (range.full || (theta > range.start + kSameAngle && theta < range.start + range.span - kSameAngle))
    points.push_back({theta, corner});
}

// Sorted, without duplicates; for the whole circle the first one (theta = 0) is repeated at 2 pi.
std::vector<BreakPoint> break_points(const BoreholeBoxSpec& s, const AngularRange& range) {
  std::vector<BreakPoint> points;
  if (!range.full) points = {{range.start, -1}, {range.start + range.span, -1}};
  for (int c = 0; c < 4; ++c) {
    const std::array<double, 2> p = corner_point(s, c);
    if (p[0] != s.axis[0] || p[1] != s.axis[1])
      add_if_inside(range, std::atan2(p[1] - s.axis[1], p[0] - s.axis[0]), c, points);
  }
  for (int q = 0; q < 4; ++q) add_if_inside(range, q * kPi / 2, -1, points);
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.theta < b.theta; });
  std::vector<BreakPoint> unique;
  for (const BreakPoint& p : points)
    if (unique.empty() || p.theta - unique.back().theta > kSameAngle)
      unique.push_back(p);
    else
      unique.back().corner = std::max(unique.back().corner, p.corner);  // a corner's ray must reach it
  if (range.full) {
    if (unique.back().theta > 2 * kPi - kSameAngle) unique.pop_back();
    unique.push_back({unique.front().theta + 2 * kPi, unique.front().corner});
  }
  return unique;
}

// Exact along the axis directions, so that the planes x = ax and y = ay hold their nodes exactly.
std::array<double, 2> direction(double theta) {
  const double quarter = std::round(theta / (kPi / 2));
  if (std::abs(theta - quarter * kPi / 2) > kSameAngle) return {std::cos(theta), std::sin(theta)};
  static constexpr double exact[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  const int q = (static_cast<int>(quarter) % 4 + 4) % 4;
  return {exact[q][0], exact[q][1]};
}

struct Ray {
  std::array<double, 2> dir{}, end{};  // unit direction; where it meets the box's boundary
  double length = 0;                   // R(theta): from the axis to end
};

// The end is on the side's plane exactly (the coordinate set, not computed), a corner's at the corner.
Ray make_ray(const BoreholeBoxSpec& s, const BreakPoint& at) {
  Ray ray;
  if (at.corner >= 0) {
    ray.end = corner_point(s, at.corner);
    ray.length = std::hypot(ray.end[0] - s.axis[0], ray.end[1] - s.axis[1]);
    ray.dir = {(ray.end[0] - s.axis[0]) / ray.length, (ray.end[1] - s.axis[1]) / ray.length};
    return ray;
  }
  ray.dir = direction(at.theta);
  ray.length = std::numeric_limits<double>::infinity();
  int hit = 0;
  for (int a = 0; a < 2; ++a) {
    if (ray.dir[a] == 0) continue;
    const double t = ((ray.dir[a] > 0 ? s.hi[a] : s.lo[a]) - s.axis[a]) / ray.dir[a];
    if (t < ray.length) ray.length = t, hit = a;
  }
  ray.end = {s.axis[0] + ray.length * ray.dir[0], s.axis[1] + ray.length * ray.dir[1]};
  ray.end[hit] = ray.dir[hit] > 0 ? s.hi[hit] : s.lo[hit];
  return ray;
}

// The hoop's rays counter-clockwise, hoop + 1 of them (the whole circle's last is its first again); each
// segment between break points cut into equal angles of about size / radius.
template <class Visit>
void for_each_ray(const BoreholeBoxSpec& s, Visit&& visit) {
  const std::vector<BreakPoint> points = break_points(s, angular_range(s));
  for (size_t b = 0; b + 1 < points.size(); ++b) {
    const double a = points[b].theta, span = points[b + 1].theta - a;
    const int n = static_cast<int>(std::max(1.0, std::round(span * s.radius / s.size)));
    visit(make_ray(s, points[b]));
    for (int m = 1; m < n; ++m) visit(make_ray(s, {a + span * m / n, -1}));
  }
  visit(make_ray(s, points.back()));
}

// N such that the first ring on the shortest ray is about `size` thick: size (g^N - 1) / (g - 1) = the
// ray's length outside the hole (log1p / expm1: accurate for g near 1).
size_t ring_count(const BoreholeBoxSpec& s, double shortest_ray) {
  const double cells = (shortest_ray - s.radius) / s.size;
  const double n = s.growth > 1 ? std::log1p(cells * (s.growth - 1)) / std::log1p(s.growth - 1) : cells;
  if (n > kMaxCells)
    throw Error(fmt::format("borehole box: a size of {:g} m makes more than 1e7 rings", s.size));
  return static_cast<size_t>(std::max(1.0, std::round(n)));
}

// s_k = (g^k - 1) / (g^N - 1), k / N for g = 1; s_0 = 0 and s_N = 1 exactly.
std::vector<double> ring_fractions(double growth, size_t rings) {
  std::vector<double> s(rings + 1);
  const double log_g = std::log1p(growth - 1);
  for (size_t k = 0; k <= rings; ++k)
    s[k] = growth > 1
               ? std::expm1(log_g * static_cast<double>(k)) / std::expm1(log_g * static_cast<double>(rings))
               : static_cast<double>(k) / static_cast<double>(rings);
  s[rings] = 1.0;
  return s;
}

size_t layer_count(const BoreholeBoxSpec& s) {
  return static_cast<size_t>(std::max(1.0, std::round((s.hi[2] - s.lo[2]) / s.size)));
}

// Lattice node (i, j, k) -> ring i on ray j at layer k.
void place_nodes(const BoreholeBoxSpec& s, const BoreholeLatticeCounts& c, const std::vector<Ray>& rays,
                 TetMesh& mesh) {
  const std::vector<double> fraction = ring_fractions(s.growth, c.rings);
  const size_t nr = c.rings + 1, nh = c.hoop + 1;
  for (size_t v = 0; v < mesh.nodes.size(); ++v) {
    const size_t i = v % nr, j = v / nr % nh, k = v / (nr * nh);
    const Ray& ray = rays[j];
    const double r = s.radius + (ray.length - s.radius) * fraction[i];
    const double z = k == c.layers ? s.hi[2]
                                   : s.lo[2] + (s.hi[2] - s.lo[2]) * static_cast<double>(k) /
                                                   static_cast<double>(c.layers);
    if (i == c.rings)
      mesh.nodes[v] = {ray.end[0], ray.end[1], z};
    else
      mesh.nodes[v] = {s.axis[0] + r * ray.dir[0], s.axis[1] + r * ray.dir[1], z};
  }
}

// Lattice xmin is the wall, xmax the box's sides, ymin / ymax the hoop's ends (on the sides the axis sits
// on; for the whole circle the seam, which share_seam closes), zmin / zmax the ends along z.
void name_surfaces(const BoreholeBoxSpec& s, bool full, TetMesh& mesh) {
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<int32_t> surfaces;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int32_t lattice = mesh.triangle_surface[t];
    int32_t surface = lattice;
    if (lattice == kXmin) {
      surface = kBorehole;
    } else if (lattice != kZmin && lattice != kZmax) {
      if (full && lattice != kXmax) continue;
      surface = box_face_of(s.lo, s.hi, mesh, mesh.triangles[t]);
      if (surface < 0)
        throw Error("borehole box: internal error, an outer triangle lies on no side of the box");
    }
    triangles.push_back(mesh.triangles[t]);
    surfaces.push_back(surface);
  }
  mesh.triangles = std::move(triangles);
  mesh.triangle_surface = std::move(surfaces);
  mesh.surface_names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax", "borehole"};
}

// The whole circle: node (i, hoop, k) is node (i, 0, k); the copies go, the others keep their order.
void share_seam(const BoreholeLatticeCounts& c, TetMesh& mesh) {
  const size_t nr = c.rings + 1, nh = c.hoop + 1;
  std::vector<int32_t> renumber(mesh.nodes.size());
  std::vector<std::array<double, 3>> kept;
  kept.reserve(nr * c.hoop * (c.layers + 1));
  for (size_t v = 0; v < mesh.nodes.size(); ++v)
    if (v / nr % nh == c.hoop) {
      renumber[v] = renumber[v - c.hoop * nr];
    } else {
      renumber[v] = static_cast<int32_t>(kept.size());
      kept.push_back(mesh.nodes[v]);
    }
  for (auto& t : mesh.tets)
    for (int32_t& v : t) v = renumber[v];
  for (auto& t : mesh.triangles)
    for (int32_t& v : t) v = renumber[v];
  mesh.nodes = std::move(kept);
}

double orientation(const TetMesh& mesh, const std::array<int32_t, 4>& t) {
  const auto &a = mesh.nodes[t[0]], &b = mesh.nodes[t[1]], &c = mesh.nodes[t[2]], &d = mesh.nodes[t[3]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// The map keeps orientation because every lattice cell becomes a convex quad times a layer; checked, as
// a wrong tet would only show up later as a solver blowing up.
void check_positive(const TetMesh& mesh) {
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    if (!(orientation(mesh, mesh.tets[t]) > 0))
      throw Error(fmt::format("borehole box: internal error, tet {} is not positively oriented", t));
}

}  // namespace

BoreholeLatticeCounts borehole_box_counts(const BoreholeBoxSpec& spec) {
  check(spec);
  BoreholeLatticeCounts counts;
  double shortest = std::numeric_limits<double>::infinity();
  size_t rays = 0;
  for_each_ray(spec, [&](const Ray& ray) {
    ++rays;
    shortest = std::min(shortest, ray.length);
  });
  counts.hoop = rays - 1;
  counts.rings = ring_count(spec, shortest);
  counts.layers = layer_count(spec);
  return counts;
}

TetMesh borehole_box(const BoreholeBoxSpec& spec) {
  const BoreholeLatticeCounts c = borehole_box_counts(spec);
  if (static_cast<double>(c.rings + 1) * static_cast<double>(c.hoop + 1) * static_cast<double>(c.layers + 1) >
      std::numeric_limits<int32_t>::max())
    throw Error(fmt::format("borehole box: {} x {} x {} cells need more than 2^31 nodes; use a larger size",
                            c.rings, c.hoop, c.layers));
  std::vector<Ray> rays;
  for_each_ray(spec, [&](const Ray& ray) { rays.push_back(ray); });
  TetMesh mesh = generate_lattice_box(
      {static_cast<int>(c.rings), static_cast<int>(c.hoop), static_cast<int>(c.layers)}, {1, 1, 1});
  place_nodes(spec, c, rays, mesh);
  const bool full = angular_range(spec).full;
  name_surfaces(spec, full, mesh);
  if (full) share_seam(c, mesh);
  check_positive(mesh);
  return mesh;
}

BoreholeBoxSpec borehole_box_spec(const std::array<double, 3>& origin, const std::array<double, 3>& extent,
                                  const BoreholeMeshSpec& hole) {
  BoreholeBoxSpec spec;
  spec.lo = origin;
  for (int d = 0; d < 3; ++d) spec.hi[size_t(d)] = origin[size_t(d)] + extent[size_t(d)];
  spec.axis = {hole.axis_x, hole.axis_y};
  spec.radius = hole.radius;
  spec.size = hole.size;
  spec.growth = hole.growth;
  return spec;
}

}  // namespace rift
