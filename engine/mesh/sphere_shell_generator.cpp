// Quarter spherical shell on CGAL Mesh_3 through polyhedral_mesher (see sphere_shell_generator.hpp).
#include "engine/mesh/sphere_shell_generator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/vec3.hpp"

namespace rift {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxFacetAngle = 3.0 * kPi / 180.0;
// Facets turn by at most 3 deg inside a sphere patch, by 90 deg at the patch borders.
constexpr double kFeatureAngleDeg = 30.0;

enum Surface : int32_t { kSphere, kOuter, kYmin, kZmin };

// Point at polar index i of na (angle from +x) and azimuth index j of nc (from +y towards +z) on the
// sphere of radius r; the planes and the poles are hit exactly (no cos(pi/2) round-off).
Vec3 sphere_point(double r, int i, int na, int j, int nc) {
  const double a = kPi * i / na, c = 0.5 * kPi * j / nc;
  const double ca = i == 0 ? 1.0 : i == na ? -1.0 : std::cos(a);
  const double sa = i == 0 || i == na ? 0.0 : std::sin(a);
  const double cc = j == 0 ? 1.0 : j == nc ? 0.0 : std::cos(c);
  const double sc = j == 0 ? 0.0 : j == nc ? 1.0 : std::sin(c);
  return {r * ca, r * sa * cc, r * sa * sc};
}

// Newell normal of a polygon (any orientation, planar).
Vec3 polygon_normal(const PolyhedralSurface& s, const std::vector<size_t>& f) {
  Vec3 n{0, 0, 0};
  for (size_t k = 0; k < f.size(); ++k) {
    const Vec3& p = s.points[f[k]];
    const Vec3& q = s.points[f[(k + 1) % f.size()]];
    n[0] += (p[1] - q[1]) * (p[2] + q[2]);
    n[1] += (p[2] - q[2]) * (p[0] + q[0]);
    n[2] += (p[0] - q[0]) * (p[1] + q[1]);
  }
  return n;
}

// The quarter sphere of radius r as triangles, oriented along `outward_sign` * (radial direction).
PolyhedralSurface quarter_sphere(double r, int na, int nc, double outward_sign) {
  PolyhedralSurface s;
  // Index 0: pole i = 0; then rows i = 1..na-1 with nc + 1 points; last: pole i = na.
  s.points.push_back(sphere_point(r, 0, na, 0, nc));
  for (int i = 1; i < na; ++i)
    for (int j = 0; j <= nc; ++j) s.points.push_back(sphere_point(r, i, na, j, nc));
  s.points.push_back(sphere_point(r, na, na, 0, nc));
  const size_t last = s.points.size() - 1;
  const auto id = [&](int i, int j) -> size_t {
    if (i == 0) return 0;
    if (i == na) return last;
    return 1 + static_cast<size_t>(i - 1) * (nc + 1) + j;
  };
  const auto add = [&](size_t a, size_t b, size_t c) {
    std::vector<size_t> f{a, b, c};
    const Vec3 n = cross(sub(s.points[b], s.points[a]), sub(s.points[c], s.points[a]));
    const Vec3& p = s.points[a];
    const Vec3 m{(p[0] + s.points[b][0] + s.points[c][0]) / 3, (p[1] + s.points[b][1] + s.points[c][1]) / 3,
                 (p[2] + s.points[b][2] + s.points[c][2]) / 3};
    if (outward_sign * dot(n, m) < 0) std::swap(f[1], f[2]);
    s.faces.push_back(f);
  };
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nc; ++j) {
      if (i == 0) {
        add(id(0, 0), id(1, j), id(1, j + 1));
      } else if (i == na - 1) {
        add(id(i, j), id(na, 0), id(i, j + 1));
      } else {
        add(id(i, j), id(i + 1, j), id(i + 1, j + 1));
        add(id(i, j), id(i + 1, j + 1), id(i, j + 1));
      }
    }
  return s;
}

// The half annulus in the plane of azimuth index j (0: z = 0, nc: y = 0), outward along -axis.
PolyhedralSurface half_annulus(double r_in, int na_in, double r_out, int na_out, int j, int nc_in, int nc_out,
                               int axis) {
  PolyhedralSurface s;
  std::vector<size_t> f;
  for (int i = 0; i <= na_out; ++i) {
    s.points.push_back(sphere_point(r_out, i, na_out, j == 0 ? 0 : nc_out, nc_out));
    f.push_back(s.points.size() - 1);
  }
  for (int i = na_in; i >= 0; --i) {
    s.points.push_back(sphere_point(r_in, i, na_in, j == 0 ? 0 : nc_in, nc_in));
    f.push_back(s.points.size() - 1);
  }
  if (polygon_normal(s, f)[axis] > 0) std::reverse(f.begin(), f.end());
  s.faces.push_back(f);
  return s;
}

int polar_facets(double radius, double h) {
  const double angle = std::min(kMaxFacetAngle, 2 * std::asin(std::min(1.0, h / (8 * radius))));
  return std::max(4, static_cast<int>(std::ceil(kPi / angle)));
}

[[noreturn]] void fail(const std::string& what) {
  throw Error("sphere shell mesh: " + what);
}

}  // namespace

TetMesh generate_sphere_shell_mesh(const SphereShellSpec& spec, Mesh3Stats* stats) {
  const double r = spec.radius, b = spec.outer_radius;
  if (!(r > 0) || !std::isfinite(r)) fail("expected radius > 0");
  if (!(b > r) || !std::isfinite(b)) fail("expected outer_radius > radius");
  if (!(spec.size_min > 0) || !(spec.size_max >= spec.size_min) || !std::isfinite(spec.size_max))
    fail("expected 0 < size_min <= size_max");
  if (!(spec.grading >= 0) || !std::isfinite(spec.grading)) fail("expected grading >= 0");
  const auto size = [spec](const Vec3& p) {
    const double d = std::sqrt(dot(p, p)) - spec.radius;
    return std::min(spec.size_max, spec.size_min + spec.grading * std::max(d, 0.0));
  };
  const int na_in = polar_facets(r, spec.size_min);
  const int na_out = polar_facets(b, size({b, 0, 0}));
  const int nc_in = std::max(2, (na_in + 1) / 2), nc_out = std::max(2, (na_out + 1) / 2);
  PolyhedralMeshInput in;
  in.patches.push_back(quarter_sphere(r, na_in, nc_in, -1.0));
  in.patches.push_back(quarter_sphere(b, na_out, nc_out, 1.0));
  in.patches.push_back(half_annulus(r, na_in, b, na_out, nc_in, nc_in, nc_out, 1));  // y = 0
  in.patches.push_back(half_annulus(r, na_in, b, na_out, 0, nc_in, nc_out, 2));      // z = 0
  in.feature_angle_deg = kFeatureAngleDeg;
  in.size = size;
  in.seed = spec.seed;
  in.surface_names = {"sphere", "outer", "ymin", "zmin"};
  const double tol = 1e-9 * b;
  in.classify = [r, b, tol](const TetMesh& mesh, const std::array<int32_t, 3>& tri) -> int32_t {
    for (const auto& [axis, surface] : {std::pair{1, kYmin}, std::pair{2, kZmin}}) {
      bool in_plane = true;
      for (const int32_t v : tri) in_plane = in_plane && std::abs(mesh.nodes[v][axis]) <= tol;
      if (in_plane) return surface;
    }
    Vec3 c{0, 0, 0};
    for (const int32_t v : tri)
      for (int d = 0; d < 3; ++d) c[d] += mesh.nodes[v][d] / 3;
    return std::sqrt(dot(c, c)) < 0.5 * (r + b) ? kSphere : kOuter;
  };
  return mesh_polyhedron(in, stats);
}

}  // namespace rift
