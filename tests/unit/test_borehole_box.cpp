// The borehole box (an O-grid Kuhn lattice around a hole along z), for the whole hole, half and quarter
// models, uniform and graded rings. Checked: every tet is positive and the volume is the box's less the
// wall polygon's; the wall's nodes are on the circle and its area is the chords'; the planes through the
// axis are lattice planes out to the sides; the mesh is conforming with every boundary triangle named,
// outward and exactly on its side; the counts match the mesh and the first ring is about `size` thick;
// bad specs throw an error that names the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/vec3.hpp"
#include "engine/mesh/borehole_box.hpp"

namespace rift {
namespace {

constexpr double kPi = std::numbers::pi;

struct Case {
  std::string name;
  BoreholeBoxSpec spec;
  double mid = 0;         // the middle of the angular range [rad]
  double span = 2 * kPi;  // its width: 2 pi for the whole hole, pi for a half, pi / 2 for a quarter model
  bool full() const { return span == 2 * kPi; }
};

std::vector<Case> cases() {
  return {
      {"full, centred, graded", {{-0.5, -0.5, 0}, {0.5, 0.5, 0.01}, {0, 0}, 0.05, 0.01, 1.1}, 0, 2 * kPi},
      {"full, off centre, uniform",
       {{0, 0, -0.01}, {0.8, 0.5, 0.01}, {0.3, 0.2}, 0.04, 0.01, 1.0},
       0,
       2 * kPi},
      {"half on xmin, graded", {{0, -0.5, 0}, {0.5, 0.5, 0.005}, {0, 0}, 0.05, 0.005, 1.05}, 0, kPi},
      {"half on ymax, uniform",
       {{-0.3, -0.6, 0}, {0.4, 0.25, 0.01}, {0.1, 0.25}, 0.05, 0.01, 1.0},
       -kPi / 2,
       kPi},
      {"quarter at xmin ymin, uniform",
       {{0, 0, 0}, {0.4, 0.3, 0.02}, {0, 0}, 0.05, 0.01, 1.0},
       kPi / 4,
       kPi / 2},
      {"quarter at xmax ymax, graded",
       {{-1, -0.5, 0}, {0.2, 0.3, 0.05}, {0.2, 0.3}, 0.08, 0.02, 1.2},
       -3 * kPi / 4,
       kPi / 2},
  };
}

double six_volume(const TetMesh& mesh, const std::array<int32_t, 4>& t) {
  const Vec3 e1 = sub(mesh.nodes[t[1]], mesh.nodes[t[0]]), e2 = sub(mesh.nodes[t[2]], mesh.nodes[t[0]]),
             e3 = sub(mesh.nodes[t[3]], mesh.nodes[t[0]]);
  return dot(e1, cross(e2, e3));
}

double area(const TetMesh& mesh, const std::array<int32_t, 3>& t) {
  return 0.5 * norm(cross(sub(mesh.nodes[t[1]], mesh.nodes[t[0]]), sub(mesh.nodes[t[2]], mesh.nodes[t[0]])));
}

double distance_from_axis(const Case& c, const Vec3& p) {
  return std::hypot(p[0] - c.spec.axis[0], p[1] - c.spec.axis[1]);
}

// The wall's hoop cells' angles, from its nodes on the bottom face sorted counter-clockwise.
std::vector<double> wall_angles(const Case& c, const TetMesh& mesh) {
  const int32_t wall = mesh.surface_index("borehole");
  std::set<int32_t> nodes;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    if (mesh.triangle_surface[t] == wall)
      for (const int32_t v : mesh.triangles[t])
        if (mesh.nodes[v][2] == c.spec.lo[2]) nodes.insert(v);
  std::vector<double> theta;  // relative to the range's middle, so that the range lies in (-pi, pi]
  for (const int32_t v : nodes) {
    const double dx = mesh.nodes[v][0] - c.spec.axis[0], dy = mesh.nodes[v][1] - c.spec.axis[1];
    theta.push_back(std::atan2(-dx * std::sin(c.mid) + dy * std::cos(c.mid),
                               dx * std::cos(c.mid) + dy * std::sin(c.mid)));
  }
  std::sort(theta.begin(), theta.end());
  std::vector<double> cells;
  for (size_t i = 1; i < theta.size(); ++i) cells.push_back(theta[i] - theta[i - 1]);
  if (c.full()) cells.push_back(theta.front() + 2 * kPi - theta.back());
  return cells;
}

double thickness(const Case& c) {
  return c.spec.hi[2] - c.spec.lo[2];
}

TEST(BoreholeBox, EveryTetIsPositiveAndTheVolumeIsTheBoxLessTheWallPolygon) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const TetMesh mesh = borehole_box(c.spec);
    double volume = 0;
    for (const auto& t : mesh.tets) {
      const double six_v = six_volume(mesh, t);
      ASSERT_GT(six_v, 0.0);
      volume += six_v / 6;
    }
    double polygon = 0;
    for (const double d : wall_angles(c, mesh)) polygon += 0.5 * c.spec.radius * c.spec.radius * std::sin(d);
    const double rectangle = (c.spec.hi[0] - c.spec.lo[0]) * (c.spec.hi[1] - c.spec.lo[1]);
    const double expected = (rectangle - polygon) * thickness(c);
    EXPECT_NEAR(volume, expected, 1e-12 * expected);
    EXPECT_EQ(mesh.tet_region, std::vector<int32_t>(mesh.tets.size(), 0));
    EXPECT_EQ(mesh.region_names, std::vector<std::string>{"domain"});
  }
}

TEST(BoreholeBox, TheWallIsOnTheCircleAndMadeOfChords) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const TetMesh mesh = borehole_box(c.spec);
    const int32_t wall = mesh.surface_index("borehole");
    ASSERT_EQ(wall, 6);
    double wall_area = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (mesh.triangle_surface[t] != wall) continue;
      for (const int32_t v : mesh.triangles[t])
        ASSERT_NEAR(distance_from_axis(c, mesh.nodes[v]), c.spec.radius, 1e-12 * c.spec.radius);
      wall_area += area(mesh, mesh.triangles[t]);
    }
    double chords = 0;
    for (const double d : wall_angles(c, mesh)) chords += 2 * c.spec.radius * std::sin(d / 2);
    EXPECT_NEAR(wall_area, chords * thickness(c), 1e-12 * wall_area);
  }
}

// Whether the direction at angle theta is in the (closed) angular range.
bool in_range(const Case& c, double theta) {
  return c.full() || std::abs(std::remainder(theta - c.mid, 2 * kPi)) <= c.span / 2 + 1e-9;
}

// On the half-plane from the axis along q * 90 degrees, exactly.
bool on_half_plane(const Case& c, const Vec3& p, int q) {
  const double dx = p[0] - c.spec.axis[0], dy = p[1] - c.spec.axis[1];
  if (q % 2 == 0) return dy == 0 && (q == 0 ? dx > 0 : dx < 0);
  return dx == 0 && (q == 1 ? dy > 0 : dy < 0);
}

TEST(BoreholeBox, ThePlanesThroughTheAxisAreLatticePlanesOutToTheSides) {
  for (const Case& c : cases()) {
    const TetMesh mesh = borehole_box(c.spec);
    const BoreholeLatticeCounts counts = borehole_box_counts(c.spec);
    int planes = 0;
    for (int q = 0; q < 4; ++q) {
      if (!in_range(c, q * kPi / 2)) continue;
      SCOPED_TRACE(c.name + ", direction " + std::to_string(90 * q));
      ++planes;
      // Its side: where the ray along q * 90 degrees meets the box.
      const int axis = q % 2, side = q < 2 ? 1 : 0;
      const double end = side ? c.spec.hi[axis] : c.spec.lo[axis];
      std::vector<double> r;
      for (const Vec3& p : mesh.nodes)
        if (p[2] == c.spec.lo[2] && on_half_plane(c, p, q))
          r.push_back(std::abs(p[axis] - c.spec.axis[axis]));
      std::sort(r.begin(), r.end());
      ASSERT_EQ(r.size(), counts.rings + 1);
      EXPECT_NEAR(r.front(), c.spec.radius, 1e-12 * c.spec.radius);
      EXPECT_EQ(r.back(), std::abs(end - c.spec.axis[axis]));
      // Tet faces tile the half-plane from the wall to the side: a crack can open along it.
      std::set<std::array<int32_t, 3>> faces;
      for (const auto& t : mesh.tets)
        for (int skip = 0; skip < 4; ++skip) {
          std::array<int32_t, 3> f;
          for (int i = 0, n = 0; i < 4; ++i)
            if (i != skip) f[n++] = t[i];
          if (std::all_of(f.begin(), f.end(),
                          [&](int32_t v) { return on_half_plane(c, mesh.nodes[v], q); })) {
            std::sort(f.begin(), f.end());
            faces.insert(f);
          }
        }
      double tiled = 0;
      for (const auto& f : faces) tiled += area(mesh, f);
      const double expected = (r.back() - c.spec.radius) * thickness(c);
      EXPECT_NEAR(tiled, expected, 1e-12 * expected);
    }
    EXPECT_EQ(planes, c.full() ? 4 : c.span == kPi ? 3 : 2) << c.name;
  }
}

std::array<int32_t, 3> sorted(std::array<int32_t, 3> f) {
  std::sort(f.begin(), f.end());
  return f;
}

// Each face of a tet: how many tets have it, and the vertex opposite it in the last one.
struct FaceUse {
  int count = 0;
  int32_t opposite = -1;
};

std::map<std::array<int32_t, 3>, FaceUse> face_uses(const TetMesh& mesh) {
  std::map<std::array<int32_t, 3>, FaceUse> uses;
  for (const auto& t : mesh.tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int32_t, 3> f;
      for (int i = 0, n = 0; i < 4; ++i)
        if (i != skip) f[n++] = t[i];
      FaceUse& use = uses[sorted(f)];
      ++use.count;
      use.opposite = t[skip];
    }
  return uses;
}

// Exactly on its side's plane (or on the circle for the wall).
bool on_its_surface(const Case& c, const TetMesh& mesh, const std::array<int32_t, 3>& tri, int32_t surface) {
  for (const int32_t v : tri) {
    const Vec3& p = mesh.nodes[v];
    if (surface == 6 ? std::abs(distance_from_axis(c, p) - c.spec.radius) > 1e-12 * c.spec.radius
                     : p[surface / 2] != (surface % 2 ? c.spec.hi[surface / 2] : c.spec.lo[surface / 2]))
      return false;
  }
  return true;
}

TEST(BoreholeBox, TheMeshIsConformingAndEveryBoundaryTriangleIsNamedOutwardAndOnItsSide) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const TetMesh mesh = borehole_box(c.spec);
    EXPECT_EQ(mesh.surface_names,
              (std::vector<std::string>{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax", "borehole"}));
    const auto uses = face_uses(mesh);
    size_t boundary = 0;
    for (const auto& [face, use] : uses) {
      ASSERT_LE(use.count, 2);
      boundary += use.count == 1;
    }
    ASSERT_EQ(mesh.triangles.size(), mesh.triangle_surface.size());
    EXPECT_EQ(boundary, mesh.triangles.size());
    std::set<std::array<int32_t, 3>> named;
    std::vector<int> per_surface(7, 0);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const auto it = uses.find(sorted(tri));
      ASSERT_TRUE(it != uses.end() && it->second.count == 1) << "triangle " << t << " is no boundary face";
      ASSERT_TRUE(named.insert(sorted(tri)).second) << "triangle " << t << " twice";
      const int32_t s = mesh.triangle_surface[t];
      ASSERT_TRUE(s >= 0 && s < 7);
      ++per_surface[s];
      EXPECT_TRUE(on_its_surface(c, mesh, tri, s)) << "triangle " << t << " on " << mesh.surface_names[s];
      const std::array<int32_t, 4> inward = {tri[0], tri[1], tri[2], it->second.opposite};
      EXPECT_LT(six_volume(mesh, inward), 0.0) << "triangle " << t << " faces inward";
    }
    for (const int s : {1, 3, 4, 5, 6}) EXPECT_GT(per_surface[s], 0) << mesh.surface_names[s];
  }
}

TEST(BoreholeBox, TheCountsAreTheMeshsAndTheFirstRingIsAboutTheSize) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const TetMesh mesh = borehole_box(c.spec);
    const BoreholeLatticeCounts n = borehole_box_counts(c.spec);
    EXPECT_EQ(mesh.tets.size(), n.tets());
    const size_t rays = c.full() ? n.hoop : n.hoop + 1;
    ASSERT_EQ(mesh.nodes.size(), (n.rings + 1) * rays * (n.layers + 1));
    // Nodes run radially fastest: ray j's ring i at the bottom is node i + (rings + 1) j.
    size_t shortest = 0;
    for (size_t j = 0; j < rays; ++j)
      if (distance_from_axis(c, mesh.nodes[n.rings + (n.rings + 1) * j]) <
          distance_from_axis(c, mesh.nodes[n.rings + (n.rings + 1) * shortest]))
        shortest = j;
    const double first = distance_from_axis(c, mesh.nodes[1 + (n.rings + 1) * shortest]) - c.spec.radius;
    EXPECT_NEAR(first, c.spec.size, 0.25 * c.spec.size);
  }
  const Case half = cases()[2];  // the half model of the docs' example
  const BoreholeLatticeCounts n = borehole_box_counts(half.spec);
  EXPECT_EQ(n.hoop, 32u);   // 4 segments of 45 degrees, 8 cells of 0.05 * pi / 4 = 3.9 mm on the wall
  EXPECT_EQ(n.rings, 35u);  // log(1 + 0.45 * 0.05 / 0.005) / log(1.05) = 34.9
  EXPECT_EQ(n.layers, 1u);
  EXPECT_EQ(n.tets(), 6720u);
}

// Random boxes, axes (inside, on a side, on a corner), sizes and growths: the map never folds a tet and
// the mesh stays conforming.
TEST(BoreholeBox, RandomSpecsGiveConformingMeshesOfPositiveTetsAndTheCountedNumber) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 300; ++n) {
    BoreholeBoxSpec s;
    s.radius = 0.01 + u(rng);
    s.size = s.radius * (0.2 + 0.8 * u(rng));
    s.growth = u(rng) < 0.3 ? 1.0 : 1.0 + u(rng);
    s.axis = {4 * u(rng) - 2, 4 * u(rng) - 2};
    for (int a = 0; a < 2; ++a) {
      const int where = static_cast<int>(3 * u(rng));  // 0: the axis on lo, 1: on hi, 2: inside
      s.lo[a] = where == 0 ? s.axis[a] : s.axis[a] - s.radius * (2 + 20 * u(rng));
      s.hi[a] = where == 1 ? s.axis[a] : s.axis[a] + s.radius * (2 + 20 * u(rng));
    }
    s.lo[2] = u(rng);
    s.hi[2] = s.lo[2] + s.size * (0.5 + 3 * u(rng));
    const TetMesh mesh = borehole_box(s);
    ASSERT_EQ(mesh.tets.size(), borehole_box_counts(s).tets()) << n;
    for (const auto& t : mesh.tets) ASSERT_GT(six_volume(mesh, t), 0.0) << n;
    size_t boundary = 0;
    for (const auto& [face, use] : face_uses(mesh)) {
      ASSERT_LE(use.count, 2) << n;
      boundary += use.count == 1;
    }
    ASSERT_EQ(boundary, mesh.triangles.size()) << n;
  }
}

std::string error_of(const BoreholeBoxSpec& spec) {
  try {
    borehole_box(spec);
  } catch (const Error& e) {
    std::string counts_error;
    try {
      borehole_box_counts(spec);
    } catch (const Error& f) {
      counts_error = f.what();
    }
    EXPECT_EQ(counts_error, e.what());  // the budget sees the same error
    return e.what();
  }
  return "no error";
}

TEST(BoreholeBox, BadSpecsThrowAnErrorNamingTheProblem) {
  const BoreholeBoxSpec good = cases()[0].spec;
  auto with = [&](auto change) {
    BoreholeBoxSpec s = good;
    change(s);
    return error_of(s);
  };
  EXPECT_NE(with([](auto& s) {
              s.axis = {0.6, 0};
            }).find("expected the axis in the box's xy rectangle"),
            std::string::npos);
  EXPECT_NE(
      with([](auto& s) {
        s.axis = {0.42, 0};
      }).find("must be at least 2 radii from every side it does not sit on: xmax is 0.08 m from the axis"),
      std::string::npos);
  EXPECT_NE(with([](auto& s) {
              s.axis = {0, -0.5 + 0.09};
            }).find("ymin is 0.09 m from the axis"),
            std::string::npos);
  EXPECT_NE(with([](auto& s) { s.size = 0.06; }).find("expected a size at the wall in (0, radius]"),
            std::string::npos);
  EXPECT_NE(with([](auto& s) { s.growth = 2.5; }).find("expected a growth in [1, 2], found 2.5"),
            std::string::npos);
  EXPECT_NE(with([](auto& s) { s.radius = 0; }).find("expected a positive radius"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.hi[2] = s.lo[2]; }).find("expected lo < hi along z"), std::string::npos);
  EXPECT_EQ(with([](auto& s) { s.axis = {-0.5, 0.5}; }), "no error");  // a corner: a quarter model
}

}  // namespace
}  // namespace rift
