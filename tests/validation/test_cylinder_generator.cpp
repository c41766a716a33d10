// Disc (cylinder) generator for the Brazilian test: the outline is the documented inscribed polygon,
// the mesh is inscribed in the polygon prism (closed, outward, boundary nodes on the prism, volume and
// areas between exact bounds), the loading arcs are made of whole triangles, tets are positive, sizes
// follow the field, the mesh is reproducible, and a scene with a cylinder builds a world.
//
// Tolerances. "On the prism": 1e-12 R. Mesh_3 places surface nodes by exact intersection with the
// input facets, then rounds them to double (1e-16 relative), so 1e-12 only guards round-off; a node
// off the surface by any meshing error would be off by a fraction of the element size (1e-3 R and
// up). Sums over the closed boundary (area vectors, flux = 3 V): 1e-9 relative, as for the box
// (test_box_generator.cpp): rounding over 1e3 - 1e4 triangles adds about 1e-13. Volume and area
// bounds are exact inequalities, given 1e-12 relative for rounding.
//
// In tests/validation (ci preset, Release) rather than tests/unit: under the sanitizers each CGAL Mesh_3
// disc takes 110-210 s, 400 s of the suite's wall time on 2 cores.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "engine/core/error.hpp"
#include "engine/core/vec3.hpp"
#include "engine/mesh/cylinder_generator.hpp"
#include "engine/mesh/mesh_quality.hpp"
#include "engine/scene/load_scene.hpp"
#include "engine/world.hpp"
#include "systems/world_builder.hpp"

namespace rift {
namespace {

constexpr double kRel = 1e-9;
constexpr double kPi = std::numbers::pi;

// 50 mm x 20 mm disc off the origin, 15 deg arcs, graded from 3 mm at the arcs to 10 mm: about 1,300
// tets, well under a second.
MeshGenerateSpec disc_spec() {
  MeshGenerateSpec s;
  s.shape = MeshGenerateSpec::Shape::cylinder;
  s.cylinder = {0.05, 0.02, 15.0};
  s.origin = {0.01, -0.02, 0.003};
  s.size_min = 0.003;
  s.size_max = 0.01;
  s.grading = 0.5;
  return s;
}

const TetMesh& disc_mesh() {
  static const TetMesh mesh = generate_cylinder_mesh(disc_spec());
  return mesh;
}

// The fewest equal facets over `span` rad with chords <= size_min / 4 and at most 5 deg (the
// documented rule).
int facets(double span, double size_min, double r) {
  int n = 1;
  while (2 * r * std::sin(span / (2 * n)) > size_min / 4 || span / n > 5 * kPi / 180) ++n;
  return n;
}

// Angle of a node around the disc axis, in (-pi, pi].
double angle_of(const MeshGenerateSpec& s, const Vec3& p) {
  return std::atan2(p[1] - s.origin[1], p[0] - s.origin[0]);
}

TEST(CylinderGenerator, OutlineFollowsTheDocumentedRule) {
  const MeshGenerateSpec s = disc_spec();
  const DiscShape d = make_disc(s);
  const double r = 0.025, a = 7.5 * kPi / 180;
  EXPECT_EQ(d.load_facets, facets(2 * a, s.size_min, r));
  EXPECT_EQ(d.side_facets, facets(kPi - 2 * a, s.size_min, r));
  EXPECT_EQ(d.polygon.size(), static_cast<size_t>(2 * (d.load_facets + d.side_facets)));
  // Vertices on the circle, arc ends among them.
  for (const auto& q : d.polygon) EXPECT_NEAR(std::hypot(q[0] - 0.01, q[1] + 0.02), r, 1e-15);
  const auto& top_first = d.polygon[d.side_facets];
  EXPECT_NEAR(std::atan2(top_first[1] + 0.02, top_first[0] - 0.01), kPi / 2 - a, 1e-14);
  const double polygon = r * r *
                         (d.load_facets * std::sin(2 * a / d.load_facets) +
                          d.side_facets * std::sin((kPi - 2 * a) / d.side_facets));
  EXPECT_NEAR(disc_polygon_area(d), polygon, 1e-15);
}

// Longest edge of the triangles of the curved side (load_top, load_bottom, side).
double longest_side_edge(const TetMesh& m) {
  double longest = 0;
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    if (m.surface_names[m.triangle_surface[i]][0] == 'z') continue;
    const auto& t = m.triangles[i];
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, norm(sub(m.nodes[t[k]], m.nodes[t[(k + 1) % 3]])));
  }
  return longest;
}

TEST(CylinderGenerator, IsInscribedInThePolygonPrism) {
  const MeshGenerateSpec s = disc_spec();
  const TetMesh& m = disc_mesh();
  const DiscShape d = make_disc(s);
  const double r = 0.025, t = 0.02, a = 7.5 * kPi / 180, z0 = 0.003;
  EXPECT_EQ(m.surface_names, (std::vector<std::string>{"load_top", "load_bottom", "side", "zmin", "zmax"}));
  EXPECT_EQ(m.region_names, (std::vector<std::string>{"domain"}));

  double volume = 0;
  size_t non_positive = 0;
  for (const auto& tet : m.tets) {
    const TetShape shape = tet_shape(m.nodes[tet[0]], m.nodes[tet[1]], m.nodes[tet[2]], m.nodes[tet[3]]);
    volume += shape.six_volume / 6;
    non_positive += shape.six_volume <= 0;
  }
  EXPECT_EQ(non_positive, 0u);

  // Closed and outward: area vectors sum to zero and int (x - o) . n dA = 3 V. Boundary nodes lie on
  // the prism: in the plane of their flat face, or on the polygon facet their angle falls in.
  std::map<std::string, double> area;
  Vec3 sum{0, 0, 0};
  double flux = 0, total = 0, off_prism = 0;
  const size_t n = d.polygon.size();
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& tri = m.triangles[i];
    const std::string& name = m.surface_names[m.triangle_surface[i]];
    const Vec3 a2 = cross(sub(m.nodes[tri[1]], m.nodes[tri[0]]), sub(m.nodes[tri[2]], m.nodes[tri[0]]));
    area[name] += 0.5 * norm(a2);
    total += 0.5 * norm(a2);
    for (int k = 0; k < 3; ++k) {
      const double c = (m.nodes[tri[0]][k] + m.nodes[tri[1]][k] + m.nodes[tri[2]][k]) / 3 - s.origin[k];
      sum[k] += 0.5 * a2[k], flux += 0.5 * a2[k] * c / 3;
    }
    for (const int32_t v : tri) {
      const Vec3& p = m.nodes[v];
      if (name == "zmin" || name == "zmax") {
        off_prism = std::max(off_prism, std::abs(p[2] - (name == "zmin" ? z0 : z0 + t)));
        continue;
      }
      // The facet whose angular range holds the node: the signed distance to its line is zero.
      double best = 1;
      for (size_t f = 0; f < n; ++f) {
        const auto& q0 = d.polygon[f];
        const auto& q1 = d.polygon[(f + 1) % n];
        const double ex = q1[0] - q0[0], ey = q1[1] - q0[1], len = std::hypot(ex, ey);
        const double along = ((p[0] - q0[0]) * ex + (p[1] - q0[1]) * ey) / len;
        if (along < -1e-12 * r || along > len + 1e-12 * r) continue;
        best = std::min(best, std::abs((p[0] - q0[0]) * ey - (p[1] - q0[1]) * ex) / len);
      }
      off_prism = std::max(off_prism, best);
    }
  }
  EXPECT_LT(off_prism, 1e-12 * r);
  EXPECT_LT(norm(sum), kRel * total);
  EXPECT_NEAR(flux, volume, kRel * volume);

  // Inscribed: volume and flat-face areas at most the prism's. Each side triangle of longest edge L
  // cuts at most the sagitta L^2 / (8 R) into the prism, which bounds what is lost: side area x
  // sagitta of volume, perimeter x sagitta of each flat face.
  const double polygon = disc_polygon_area(d), sagitta = std::pow(longest_side_edge(m), 2) / (8 * r);
  EXPECT_LE(volume, polygon * t * (1 + 1e-12));
  EXPECT_GE(volume, polygon * t - 2 * kPi * r * t * sagitta);
  for (const char* face : {"zmin", "zmax"}) {
    EXPECT_LE(area[face], polygon * (1 + 1e-12)) << face;
    EXPECT_GE(area[face], polygon - 2 * kPi * r * sagitta) << face;
  }
  // A loading arc spans its whole angle between the protected arc-end lines: its area lies between
  // the flat chord's and the polygon strip's.
  const double strip = d.load_facets * 2 * r * std::sin(a / d.load_facets) * t,
               chord = 2 * r * std::sin(a) * t;
  for (const char* arc : {"load_top", "load_bottom"}) {
    EXPECT_LE(area[arc], strip * (1 + 1e-12)) << arc;
    EXPECT_GE(area[arc], chord * (1 - 1e-12)) << arc;
  }
  std::printf("volume %.6e (prism %.6e, circle %.6e); load_top %.6e (strip %.6e, chord %.6e)\n", volume,
              polygon * t, kPi * r * r * t, area["load_top"], strip, chord);
}

// Every triangle of a loading arc has all its vertices within the arc's angles, every side triangle
// all of them outside the open arcs: no triangle straddles an arc end. Tolerance 1e-12 rad: vertices
// at the arc ends carry its angle up to round-off of cos/sin and atan2 (1e-16).
TEST(CylinderGenerator, LoadingArcsAreWholeTriangles) {
  const MeshGenerateSpec s = disc_spec();
  const TetMesh& m = disc_mesh();
  const double half = 7.5 * kPi / 180, tol = 1e-12;
  const int32_t top = m.surface_index("load_top"), bottom = m.surface_index("load_bottom");
  const int32_t side = m.surface_index("side");
  std::map<int32_t, size_t> count;
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    const int32_t surface = m.triangle_surface[i];
    ++count[surface];
    for (const int32_t v : m.triangles[i]) {
      const double angle = angle_of(s, m.nodes[v]);
      const double from_top = std::abs(angle - kPi / 2), from_bottom = std::abs(angle + kPi / 2);
      if (surface == top) {
        EXPECT_LE(from_top, half + tol) << angle;
      } else if (surface == bottom) {
        EXPECT_LE(from_bottom, half + tol) << angle;
      } else if (surface == side) {
        EXPECT_GE(std::min(from_top, from_bottom), half - tol) << angle;
      }
    }
  }
  EXPECT_GT(count[top], 0u);
  EXPECT_GT(count[bottom], 0u);
}

// Sizes, with the same reasoning and thresholds as the box (test_box_generator.cpp, expect_sizes):
// Mesh_3 bounds circumradii by h at the circumcentre except inside protecting balls and after sliver
// removal, so 97 % of tets meet it exactly and all edges stay below 1.5 x 2h. Grading: tets near the
// arcs are smaller than far from them, and the graded mesh lies between the uniform meshes at
// size_max and at size_min. (Far tets do not reach size_max here: 20 mm thickness for h = 10 mm.)
TEST(CylinderGenerator, FollowsTheSizingField) {
  const MeshGenerateSpec s = disc_spec();
  const TetMesh& m = disc_mesh();
  const DiscShape d = make_disc(s);
  size_t meets = 0, near_n = 0, far_n = 0;
  double worst_edge = 0, near_sum = 0, far_sum = 0;
  for (const auto& t : m.tets) {
    const TetShape shape = tet_shape(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
    const double h = disc_mesh_size_at(s, d, shape.circumcenter);
    meets += shape.circumradius <= h * (1 + 1e-12);
    worst_edge = std::max(worst_edge, shape.max_edge / (2 * h));
    Vec3 c{0, 0, 0};
    for (const int32_t v : t)
      for (int k = 0; k < 3; ++k) c[k] += m.nodes[v][k] / 4;
    if (distance_to_load_arcs(d, c) < s.size_min) near_sum += shape.max_edge, ++near_n;
    if (disc_mesh_size_at(s, d, c) == s.size_max) far_sum += shape.max_edge, ++far_n;
  }
  EXPECT_GT(static_cast<double>(meets), 0.97 * static_cast<double>(m.tets.size()));
  EXPECT_LT(worst_edge, 1.5);
  ASSERT_GT(near_n, 0u);
  ASSERT_GT(far_n, 0u);
  EXPECT_LT(near_sum / near_n, far_sum / far_n);
  MeshGenerateSpec coarse = s, fine = s;
  coarse.size_min = s.size_max;
  fine.size_max = s.size_min;
  const size_t coarse_tets = generate_cylinder_mesh(coarse).tets.size();
  const size_t fine_tets = generate_cylinder_mesh(fine).tets.size();
  EXPECT_LT(coarse_tets, m.tets.size());
  EXPECT_LT(m.tets.size(), fine_tets);
  std::printf(
      "%zu tets (uniform size_max %zu, size_min %zu), %zu meet R <= h; worst edge %.3f x 2h; mean longest "
      "edge near the arcs %.4g m, far %.4g m\n",
      m.tets.size(), coarse_tets, fine_tets, meets, worst_edge, near_sum / near_n, far_sum / far_n);
}

TEST(CylinderGenerator, SameSeedGivesIdenticalMesh) {
  const TetMesh& first = disc_mesh();
  const TetMesh second = generate_cylinder_mesh(disc_spec());
  EXPECT_EQ(first.nodes, second.nodes);  // bit for bit
  EXPECT_EQ(first.tets, second.tets);
  EXPECT_EQ(first.triangles, second.triangles);
  EXPECT_EQ(first.triangle_surface, second.triangle_surface);
}

void expect_spec_error(const MeshGenerateSpec& spec, const std::string& fragment) {
  try {
    make_disc(spec);
    ADD_FAILURE() << "no error for " << fragment;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(CylinderGenerator, RejectsImpossibleDiscs) {
  MeshGenerateSpec s = disc_spec();
  s.cylinder.load_arc = 90;
  expect_spec_error(s, "cylinder.load_arc: expected an angle in (0, 90) deg, found 90");
  s = disc_spec();
  s.cylinder.diameter = 0;
  expect_spec_error(s, "cylinder.diameter: expected a positive length");
  s = disc_spec();
  s.size_max = 0.001;
  expect_spec_error(s, "size_max: expected a length >= size_min");
  s = disc_spec();
  s.size_min = 1e-9;  // more than 36,000 facets on a loading arc
  expect_spec_error(s, "size_min: expected a length >=");
}

// A scene with a cylinder reads, builds a world with a solid loaded on the arcs, and its resolved
// form reads back to the same scene.
TEST(CylinderGenerator, SceneBuildsAWorld) {
  const std::string yaml = R"(scene: {name: disc}
time: {end: 1.0e-6}
mesh:
  generate:
    cylinder: {diameter: 0.05, thickness: 0.02, load_arc: 12}
    size_min: 0.01
    size_max: 0.01
solid:
  materials:
    - {name: rock, density: 2650, young: 4.0e10, poisson: 0.25}
  boundaries:
    - {surface: load_bottom, type: fixed}
    - {surface: load_top, type: velocity, direction: [0, -0.01, 0]}
)";
  const SceneLoadResult r = read_scene_text(yaml, "disc.yaml", ".");
  ASSERT_TRUE(r.scene) << r.errors.front().format();
  const MeshGenerateSpec& g = *r.scene->mesh.generate;
  EXPECT_EQ(g.shape, MeshGenerateSpec::Shape::cylinder);
  EXPECT_EQ(g.cylinder.load_arc, 12.0);
  const SceneLoadResult again = read_scene_text(r.scene->resolved_yaml, "resolved.yaml", ".");
  ASSERT_TRUE(again.scene) << again.errors.front().format();
  EXPECT_EQ(again.scene->hash, r.scene->hash);

  const auto world = build_world(*r.scene);
  EXPECT_GT(world->mesh.tets.size(), 0u);
  EXPECT_EQ(world->mesh_quality.inverted, 0u);
  EXPECT_TRUE(world->store.has("solid_node"));
  EXPECT_GT(world->stable_dt(), 0.0);
  EXPECT_TRUE(std::isfinite(world->stable_dt()));
}

}  // namespace
}  // namespace rift
