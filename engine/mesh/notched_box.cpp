#include "engine/mesh/notched_box.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "engine/core/error.hpp"

namespace rift {
namespace {

using Vec2 = std::array<double, 2>;

const char* const kFaceNames[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
const char* const kAxisNames[3] = {"x", "y", "z"};

[[noreturn]] void fail(const std::string& field, const std::string& expected, const std::string& found) {
  throw Error("mesh.generate." + field + ": expected " + expected + ", found " + found);
}

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

double cross2(const Vec2& a, const Vec2& b) {
  return a[0] * b[1] - a[1] * b[0];
}
Vec2 sub2(const Vec2& a, const Vec2& b) {
  return {a[0] - b[0], a[1] - b[1]};
}

// Closed segments ab and cd share a point (including touching and collinear overlap).
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross2(sub2(b, a), sub2(c, a)), d2 = cross2(sub2(b, a), sub2(d, a));
  const double d3 = cross2(sub2(d, c), sub2(a, c)), d4 = cross2(sub2(d, c), sub2(b, c));
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on = [](const Vec2& p, const Vec2& q, const Vec2& r, double side) {  // r on segment pq, collinear
    return side == 0 && std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
           std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = sub2(b, a), ap = sub2(p, a);
  const double len2 = ab[0] * ab[0] + ab[1] * ab[1];
  const double u = std::clamp((ap[0] * ab[0] + ap[1] * ab[1]) / len2, 0.0, 1.0);
  return std::hypot(ap[0] - u * ab[0], ap[1] - u * ab[1]);
}

void check_sizes(const MeshGenerateSpec& spec) {
  for (int k = 0; k < 3; ++k)
    if (!(spec.size[k] > 0) || !std::isfinite(spec.size[k]))
      fail(std::string("size[") + std::to_string(k) + "]", "a positive length", num(spec.size[k]));
  if (!(spec.size_min > 0) || !std::isfinite(spec.size_min))
    fail("size_min", "a positive length", num(spec.size_min));
  if (!(spec.size_max >= spec.size_min) || !std::isfinite(spec.size_max))
    fail("size_max", "a length >= size_min (" + num(spec.size_min) + ")", num(spec.size_max));
  if (!(spec.grading >= 0) || !std::isfinite(spec.grading))
    fail("grading", "a number >= 0", num(spec.grading));
}

struct Face {
  int axis;
  bool max;
};

Face parse_face(const std::string& field, const std::string& face) {
  for (int f = 0; f < 6; ++f)
    if (face == kFaceNames[f]) return {f / 2, f % 2 == 1};
  fail(field, "one of xmin xmax ymin ymax zmin zmax", "'" + face + "'");
}

// Checks one notch against the box; returns its through axis.
int check_notch(const MeshGenerateSpec& spec, size_t i) {
  const NotchSpec& n = spec.notches[i];
  const std::string field = "notches[" + std::to_string(i) + "]";
  const Face face = parse_face(field + ".face", n.face);
  if (n.opening_axis < 0 || n.opening_axis > 2 || n.opening_axis == face.axis)
    fail(field + ".opening_axis",
         std::string("an axis along face ") + n.face + " (not " + kAxisNames[face.axis] + ")",
         std::to_string(n.opening_axis));
  const int a = n.opening_axis;
  if (!(n.depth > 0) || !(n.depth < spec.size[face.axis]))
    fail(field + ".depth",
         "0 < depth < " + num(spec.size[face.axis]) + " (box size along " + kAxisNames[face.axis] + ")",
         num(n.depth));
  if (!(n.opening > 0)) fail(field + ".opening", "a positive width", num(n.opening));
  const double lo = spec.origin[a], hi = spec.origin[a] + spec.size[a];
  if (!(n.center - n.opening / 2 > lo) || !(n.center + n.opening / 2 < hi))
    fail(field + ".center",
         "the opening [center -+ opening/2] strictly inside (" + num(lo) + ", " + num(hi) + ")",
         "center " + num(n.center) + " with opening " + num(n.opening));
  for (const char* box_face : kFaceNames)
    if (n.name == box_face || n.name.empty())
      fail(field + ".name", "a surface name other than the box faces", "'" + n.name + "'");
  return 3 - face.axis - a;
}

// One side of the cross-section rectangle, walked counterclockwise.
struct Side {
  Vec2 start, dir, inward;
  double length;
};

std::array<Side, 4> rectangle_sides(const NotchedBox& b) {
  const double s0 = b.lo[b.axis[0]], s1 = b.hi[b.axis[0]], t0 = b.lo[b.axis[1]], t1 = b.hi[b.axis[1]];
  return {Side{{s0, t0}, {1, 0}, {0, 1}, s1 - s0}, Side{{s1, t0}, {0, 1}, {-1, 0}, t1 - t0},
          Side{{s1, t1}, {-1, 0}, {0, -1}, s1 - s0}, Side{{s0, t1}, {0, -1}, {1, 0}, t1 - t0}};
}

// Which rectangle side a face is, given cross-section axes (s, t): t-min, s-max, t-max, s-min.
int side_of(const NotchedBox& b, const Face& f) {
  if (f.axis == b.axis[1]) return f.max ? 2 : 0;
  return f.max ? 1 : 3;
}

void add_vertex(NotchedBox& b, const Side& side, double along, double inward, int edge_label) {
  b.polygon.push_back({side.start[0] + along * side.dir[0] + inward * side.inward[0],
                       side.start[1] + along * side.dir[1] + inward * side.inward[1]});
  b.edge_notch.push_back(edge_label);
}

// Walks the rectangle counterclockwise, inserting each notch's vertices where it opens.
void build_polygon(NotchedBox& b, const MeshGenerateSpec& spec) {
  const auto sides = rectangle_sides(b);
  for (int k = 0; k < 4; ++k) {
    const Side& side = sides[k];
    std::vector<std::pair<double, size_t>> on_side;  // (position of the centre along the side, notch)
    for (size_t i = 0; i < spec.notches.size(); ++i) {
      const NotchSpec& n = spec.notches[i];
      if (side_of(b, parse_face("", n.face)) != k) continue;
      const double c = n.center - side.start[side.dir[0] != 0 ? 0 : 1];
      on_side.emplace_back(c * (side.dir[0] + side.dir[1]), i);
    }
    std::sort(on_side.begin(), on_side.end());
    add_vertex(b, side, 0, 0, -1);
    double previous_end = 0;
    for (const auto& [c, i] : on_side) {
      const NotchSpec& n = spec.notches[i];
      const int label = static_cast<int>(i);
      if (!(c - n.opening / 2 > previous_end))
        fail("notches[" + std::to_string(i) + "]", "notches on one face that do not overlap",
             "an opening overlapping another notch on face " + n.face);
      add_vertex(b, side, c - n.opening / 2, 0, label);
      if (n.shape == NotchSpec::Shape::wedge) {
        add_vertex(b, side, c, n.depth, label);
      } else {
        add_vertex(b, side, c - n.opening / 2, n.depth, label);
        add_vertex(b, side, c + n.opening / 2, n.depth, label);
      }
      add_vertex(b, side, c + n.opening / 2, 0, -1);
      previous_end = c + n.opening / 2;
    }
  }
}

std::string edge_owner(const NotchedBox& b, size_t e) {
  return b.edge_notch[e] < 0 ? "the box boundary" : "notches[" + std::to_string(b.edge_notch[e]) + "]";
}

// The polygon must be simple (no two non-adjacent edges meet) and turn by at least 5 degrees at every
// vertex: sharp-edge detection needs the faces of the prism to meet at a visible angle.
void check_polygon(const NotchedBox& b) {
  const size_t n = b.polygon.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing vertex
      if (segments_meet(b.polygon[i], b.polygon[(i + 1) % n], b.polygon[j], b.polygon[(j + 1) % n]))
        fail("notches", "notches that do not cross each other or the box boundary",
             edge_owner(b, i) + " meeting " + edge_owner(b, j));
    }
  for (size_t i = 0; i < n; ++i) {
    const Vec2 in = sub2(b.polygon[i], b.polygon[(i + n - 1) % n]),
               out = sub2(b.polygon[(i + 1) % n], b.polygon[i]);
    const double cosine =
        (in[0] * out[0] + in[1] * out[1]) / (std::hypot(in[0], in[1]) * std::hypot(out[0], out[1]));
    if (cosine > std::cos(5.0 * std::numbers::pi / 180.0))
      fail("notches", "notch faces meeting the box face at 5 degrees or more (a deeper or narrower notch)",
           edge_owner(b, i) + " nearly flush with its neighbour");
  }
}

}  // namespace

NotchedBox make_notched_box(const MeshGenerateSpec& spec) {
  check_sizes(spec);
  NotchedBox b;
  int through = 2;
  for (size_t i = 0; i < spec.notches.size(); ++i) {
    const int w = check_notch(spec, i);
    if (i > 0 && w != through)
      fail("notches[" + std::to_string(i) + "]",
           std::string("a notch running along ") + kAxisNames[through] + " like notches[0]",
           std::string("one running along ") + kAxisNames[w]);
    through = w;
  }
  b.axis = {(through + 1) % 3, (through + 2) % 3, through};
  for (int k = 0; k < 3; ++k) b.lo[k] = spec.origin[k], b.hi[k] = spec.origin[k] + spec.size[k];
  build_polygon(b, spec);
  check_polygon(b);
  b.surface_names.assign(std::begin(kFaceNames), std::end(kFaceNames));
  for (const NotchSpec& n : spec.notches) {
    auto it = std::find(b.surface_names.begin(), b.surface_names.end(), n.name);
    if (it == b.surface_names.end()) it = b.surface_names.insert(b.surface_names.end(), n.name);
    b.notch_surface.push_back(static_cast<int>(it - b.surface_names.begin()));
  }
  return b;
}

std::array<double, 3> to_3d(const NotchedBox& b, double s, double t, double w) {
  std::array<double, 3> p;
  p[b.axis[0]] = s;
  p[b.axis[1]] = t;
  p[b.axis[2]] = w;
  return p;
}

double distance_to_notches(const NotchedBox& b, const std::array<double, 3>& p, int notch) {
  const Vec2 q{p[b.axis[0]], p[b.axis[1]]};
  const int w = b.axis[2];
  const double dw = std::max({0.0, b.lo[w] - p[w], p[w] - b.hi[w]});  // beyond the through extent
  double d = std::numeric_limits<double>::infinity();
  const size_t n = b.polygon.size();
  for (size_t i = 0; i < n; ++i)
    if (b.edge_notch[i] >= 0 && (notch < 0 || b.edge_notch[i] == notch))
      d = std::min(d, segment_distance(q, b.polygon[i], b.polygon[(i + 1) % n]));
  return std::hypot(d, dw);
}

double mesh_size_at(const MeshGenerateSpec& spec, const NotchedBox& b, const std::array<double, 3>& p) {
  if (spec.notches.empty()) return spec.size_max;
  return std::min(spec.size_max, spec.size_min + spec.grading * distance_to_notches(b, p));
}

}  // namespace rift
