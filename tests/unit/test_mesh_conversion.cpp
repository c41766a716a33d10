// Mesh conversion (issue 5): the discontinuous solid mesh as a continuous volume mesh and a continuous
// surface mesh. Every figure checked here is fixed by topology, not chosen: counts follow from the mesh,
// Euler characteristics from the surfaces' topology (2 for a sphere), volumes from the divergence
// theorem. Volume tolerance 1e-12 relative: the surface sums O(1e3) triple products of coordinates of
// order 1, each exact to 1e-16, so round-off is ~1e-14; a missing or flipped triangle changes the
// volume by at least the volume of one tet's cone, ~1e-3 here.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "engine/mesh/box_generator.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "tests/unit/test_conversion_support.hpp"

namespace rift {
namespace {

using test::analyse_surface;
using test::ConversionCase;
using test::make_case;

constexpr double kVolumeRel = 1e-12;

TetMesh cgal_cube() {
  MeshGenerateSpec spec;
  spec.size = {1.0, 1.0, 1.0};
  spec.size_min = spec.size_max = 0.3;
  return generate_box_mesh(spec);
}

// Breaks every joint whose face centroid satisfies `on` (in joint order); returns how many.
size_t break_where(MeshConversion& conv, const ConversionCase& c,
                   const std::function<bool(const std::array<double, 3>&)>& on) {
  size_t n = 0;
  for (size_t j = 0; j < c.joints(); ++j)
    if (on(c.joint_centroid(j))) n += conv.break_joint(static_cast<int32_t>(j), 1e-3 * double(j));
  return n;
}

bool near(double a, double b) {
  return std::abs(a - b) < 1e-9;
}

// The paper's Fig. 4: one cube as the discontinuous mesh (4 nodes per tet, a joint on every interior
// face), the continuous volume mesh (the input mesh again) and the continuous surface mesh (the
// box's boundary triangles).
TEST(MeshConversion, Fig4CubeCountsAgreeAcrossTheThreeMeshes) {
  ConversionCase c = make_case(cgal_cube());
  const size_t T = c.mesh.tets.size(), B = c.mesh.triangles.size();
  ASSERT_GT(T, 50u);
  EXPECT_EQ(c.dm.nodes.size(), 4 * T);
  EXPECT_EQ(2 * c.joints() + B, 4 * T);  // every tet face is a joint side or a boundary triangle

  MeshConversion conv(c.topology());
  ASSERT_EQ(conv.vertex_count(), c.mesh.nodes.size());
  // With every joint intact the continuous mesh is the input mesh, vertex for vertex.
  for (size_t e = 0; e < T; ++e)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(conv.tet_vertices()[4 * e + k], c.mesh.tets[e][k]);
  EXPECT_EQ(conv.triangle_count(), B);
  EXPECT_EQ(conv.external_triangle_count(), B);

  const auto report = analyse_surface(conv, c);
  EXPECT_TRUE(report.closed_and_oriented);
  ASSERT_EQ(report.components.size(), 1u);
  EXPECT_TRUE(report.components[0].manifold);
  EXPECT_EQ(report.components[0].euler(), 2);
  EXPECT_EQ(3 * report.components[0].triangles, 2 * report.components[0].edges);
  EXPECT_NEAR(report.volume(), 1.0, kVolumeRel);

  // The volume mesh is a ball: V - E + F - T = 1.
  std::set<std::pair<int32_t, int32_t>> edges;
  std::set<std::array<int32_t, 3>> faces;
  for (size_t e = 0; e < T; ++e) {
    const int32_t* t = &conv.tet_vertices()[4 * e];
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) edges.insert({std::min(t[a], t[b]), std::max(t[a], t[b])});
      std::array<int32_t, 3> f{t[(a + 1) % 4], t[(a + 2) % 4], t[(a + 3) % 4]};
      std::sort(f.begin(), f.end());
      faces.insert(f);
    }
  }
  EXPECT_EQ(long(conv.vertex_count()) - long(edges.size()) + long(faces.size()) - long(T), 1);
  EXPECT_EQ(conv.fragment_count(), 1u);
  EXPECT_EQ(conv.fracture_surface_count(), 0u);
}

TEST(MeshConversion, PlaneThroughTheCubeGivesTwoClosedPieces) {
  ConversionCase c = make_case(generate_lattice_box({4, 4, 4}, {1, 1, 1}));
  MeshConversion conv(c.topology());
  const size_t broken = break_where(conv, c, [](const auto& p) { return near(p[0], 0.5); });
  EXPECT_EQ(broken, 2u * 4 * 4);               // two triangles per lattice square of the plane
  EXPECT_EQ(conv.vertex_count(), 125u + 25u);  // the plane's 5 x 5 vertices split in two
  EXPECT_EQ(conv.fragment_count(), 2u);
  EXPECT_EQ(conv.fracture_surface_count(), 1u);

  const auto report = analyse_surface(conv, c);
  EXPECT_TRUE(report.closed_and_oriented);
  ASSERT_EQ(report.components.size(), 2u);
  for (const auto& piece : report.components) {
    EXPECT_TRUE(piece.manifold);
    EXPECT_EQ(piece.euler(), 2);
    EXPECT_NEAR(piece.volume, 0.5, 0.5 * kVolumeRel);
  }
  EXPECT_NEAR(report.volume(), 1.0, kVolumeRel);
}

// A crack from the boundary that ends inside: the front's vertices stay shared, so one piece and one
// closed surface, a sphere with a slit (Euler 2).
TEST(MeshConversion, EdgeCrackEndingInsideKeepsOnePieceAndOneSurface) {
  ConversionCase c = make_case(generate_lattice_box({4, 4, 4}, {1, 1, 1}));
  MeshConversion conv(c.topology());
  const size_t broken = break_where(conv, c, [](const auto& p) { return near(p[0], 0.5) && p[1] < 0.5; });
  EXPECT_EQ(broken, 2u * 2 * 4);
  EXPECT_EQ(conv.vertex_count(),
            125u + 10u);  // split: y = 0 and 0.25 rows of the plane; y = 0.5 is the front
  EXPECT_EQ(conv.fragment_count(), 1u);

  const auto report = analyse_surface(conv, c);
  EXPECT_TRUE(report.closed_and_oriented);
  ASSERT_EQ(report.components.size(), 1u);
  EXPECT_TRUE(report.components[0].manifold);
  EXPECT_EQ(report.components[0].euler(), 2);
  size_t crack = 0;
  for (SurfaceTag t : conv.triangle_tag()) crack += t == SurfaceTag::fracture;
  EXPECT_EQ(crack, 2 * broken);  // both faces of every broken joint
  EXPECT_NEAR(report.volume(), 1.0, kVolumeRel);
}

// A crack wholly inside (a square "penny", 4 x 4 lattice squares): one piece, the outer surface and the
// crack's own closed surface (its two faces joined along the front), each a sphere; the crack encloses
// no volume. The two corner triangles whose three vertices all lie on the square's border are left
// intact: with them broken the crack would be pinched along their inner edge (next test).
TEST(MeshConversion, InternalCrackIsASecondClosedSurfaceOfZeroVolume) {
  ConversionCase c = make_case(generate_lattice_box({6, 6, 6}, {1, 1, 1}));
  const double lo = 1.0 / 6, hi = 5.0 / 6;
  auto on_border = [&](double y, double z) {
    return near(y, lo) || near(y, hi) || near(z, lo) || near(z, hi);
  };
  MeshConversion conv(c.topology());
  size_t broken = 0;
  for (size_t j = 0; j < c.joints(); ++j) {
    const auto p = c.joint_centroid(j);
    if (!near(p[0], 0.5) || p[1] < lo || p[1] > hi || p[2] < lo || p[2] > hi) continue;
    bool all_on_border = true;
    for (int i = 0; i < 3; ++i) {
      const auto& q = c.dm.nodes[c.dm.joints[j][i]];
      all_on_border = all_on_border && on_border(q[1], q[2]);
    }
    if (!all_on_border) broken += conv.break_joint(static_cast<int32_t>(j), 0.0);
  }
  EXPECT_EQ(broken, 2u * 4 * 4 - 2);
  EXPECT_EQ(conv.vertex_count(), 343u + 9u);  // the 3 x 3 vertices inside the front split in two
  EXPECT_EQ(conv.fragment_count(), 1u);
  const auto report = analyse_surface(conv, c);
  EXPECT_TRUE(report.closed_and_oriented);
  ASSERT_EQ(report.components.size(), 2u);
  for (const auto& s : report.components) {
    EXPECT_TRUE(s.manifold);
    EXPECT_EQ(s.euler(), 2);
  }
  EXPECT_NEAR(std::min(report.components[0].volume, report.components[1].volume), 0.0, kVolumeRel);
  EXPECT_NEAR(report.volume(), 1.0, kVolumeRel);
}

// A crack triangle whose three vertices all sit on the front stays closed: its vertices are tied, and a
// straight edge between tied ends is tied too, in the solid's own (linear) geometry. The surface there
// touches itself along that triangle's inner edge: closed and oriented still, with that edge in four
// triangles. The 2 x 2 square crack on a Kuhn lattice has two such corners.
TEST(MeshConversion, CrackPinchedAlongAnEdgeWhoseEndsAreOnTheFront) {
  ConversionCase c = make_case(generate_lattice_box({4, 4, 4}, {1, 1, 1}));
  MeshConversion conv(c.topology());
  const size_t broken = break_where(conv, c, [](const auto& p) {
    return near(p[0], 0.5) && p[1] > 0.25 && p[1] < 0.75 && p[2] > 0.25 && p[2] < 0.75;
  });
  EXPECT_EQ(broken, 2u * 2 * 2);
  EXPECT_EQ(conv.vertex_count(), 126u);  // only the crack's centre vertex is off the front
  const auto report = analyse_surface(conv, c);
  EXPECT_TRUE(report.closed_and_oriented);
  EXPECT_EQ(report.nonmanifold_edges, 2u);
  EXPECT_NEAR(report.volume(), 1.0, kVolumeRel);
}

// A fracture zone in half the block: shared nodes outside, private inside, joints on the zone's border.
// A cut along the zone's border plane still separates the block.
TEST(MeshConversion, PartialZoneWithSharedNodesOutside) {
  TetMesh mesh = generate_lattice_box({4, 4, 4}, {1, 1, 1});
  auto centroid_x = [&](size_t e) {
    double s = 0;
    for (int32_t v : mesh.tets[e]) s += mesh.nodes[v][0] / 4;
    return s;
  };
  std::vector<uint8_t> zone(mesh.tets.size());
  for (size_t e = 0; e < zone.size(); ++e) zone[e] = centroid_x(e) > 0.5;
  ConversionCase c = make_case(mesh, [&](size_t e) { return zone[e] != 0; });
  MeshConversion conv(c.topology());
  EXPECT_EQ(conv.vertex_count(), 125u);
  EXPECT_EQ(conv.triangle_count(), c.mesh.triangles.size());
  break_where(conv, c, [](const auto& p) { return near(p[0], 0.5); });
  EXPECT_EQ(conv.fragment_count(), 2u);
  const auto report = analyse_surface(conv, c);
  EXPECT_TRUE(report.closed_and_oriented);
  ASSERT_EQ(report.components.size(), 2u);
  for (const auto& s : report.components) EXPECT_EQ(s.euler(), 2);
  EXPECT_NEAR(report.volume(), 1.0, kVolumeRel);
}

TEST(MeshConversion, NotchTrianglesAreTagged) {
  ConversionCase c = make_case(generate_lattice_box({2, 2, 2}, {1, 1, 1}));
  for (size_t t = 0; t < c.mesh.triangles.size(); ++t)
    if (c.mesh.surface_names[c.mesh.triangle_surface[t]] == "zmax") c.notch.push_back(c.mesh.triangles[t]);
  MeshConversion conv(c.topology());
  size_t notch = 0;
  for (SurfaceTag t : conv.triangle_tag()) notch += t == SurfaceTag::notch;
  EXPECT_EQ(notch, 8u);
}

// Mass and momentum of the copies are those of the vertices (the means are mass-weighted).
TEST(MeshConversion, KinematicsConserveMassAndMomentum) {
  ConversionCase c = make_case(generate_lattice_box({3, 3, 3}, {1, 1, 1}));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.5, 2.0), w(-1.0, 1.0);
  for (auto& m : c.mass) m = u(rng);
  for (auto& v : c.v) v = w(rng);
  MeshConversion conv(c.topology());
  break_where(conv, c, [](const auto& p) { return near(p[1], 1.0 / 3.0); });
  conv.update_kinematics(c.x, c.v, c.mass);
  double m_nodes = 0, m_vertices = 0, p_nodes[3] = {0, 0, 0}, p_vertices[3] = {0, 0, 0};
  for (size_t n = 0; n < c.mass.size(); ++n) {
    m_nodes += c.mass[n];
    for (int k = 0; k < 3; ++k) p_nodes[k] += c.mass[n] * c.v[3 * n + k];
  }
  for (size_t i = 0; i < conv.vertex_count(); ++i) {
    m_vertices += conv.vertex_mass()[i];
    for (int k = 0; k < 3; ++k) p_vertices[k] += conv.vertex_mass()[i] * conv.vertex_v()[3 * i + k];
  }
  EXPECT_NEAR(m_vertices, m_nodes, 1e-13 * m_nodes);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p_vertices[k], p_nodes[k], 1e-12 * m_nodes);
}

// 1000 random sets of broken joints, broken in random order: the surface is closed and oriented,
// encloses the block's volume, and the pieces are the components of the tet graph through intact
// joints. The incremental state equals one built by breaking the same joints in joint order.
void fuzz(const ConversionCase& c, int sets, uint64_t seed, size_t* pinched_out) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  size_t pinched = 0;
  for (int s = 0; s < sets; ++s) {
    const double fraction = unit(rng);
    std::vector<int32_t> order(c.joints());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    order.resize(static_cast<size_t>(fraction * order.size()));
    MeshConversion conv(c.topology());
    for (int32_t j : order) conv.break_joint(j, 0.0);
    std::vector<uint8_t> intact(c.joints(), 1);
    for (int32_t j : order) intact[j] = 0;

    const auto report = analyse_surface(conv, c);
    ASSERT_TRUE(report.closed_and_oriented) << "set " << s;
    ASSERT_NEAR(report.volume(), 1.0, kVolumeRel) << "set " << s;
    for (const auto& piece : report.components) {
      ASSERT_GT(piece.volume, -kVolumeRel) << "set " << s;  // outward: no piece inside out
      if (piece.manifold) {
        ASSERT_LE(piece.euler(), 2) << "set " << s;  // a closed orientable surface: 2 - 2 genus
        ASSERT_EQ(piece.euler() % 2, 0) << "set " << s;
      }
    }
    pinched += report.nonmanifold_edges > 0 || report.pinched_vertices > 0;
    ASSERT_EQ(conv.fragment_count(), test::tet_graph_components(c, intact)) << "set " << s;
    ASSERT_EQ(conv.triangle_count(), c.mesh.triangles.size() + 2 * order.size());

    std::vector<int32_t> sorted_order = order;
    std::sort(sorted_order.begin(), sorted_order.end());
    MeshConversion again(c.topology());
    for (int32_t j : sorted_order) again.break_joint(j, 0.0);
    ASSERT_EQ(test::canonical_partition(conv), test::canonical_partition(again)) << "set " << s;
  }
  *pinched_out = pinched;
}

TEST(MeshConversion, FuzzRandomBreaksOnALattice) {
  const ConversionCase c = make_case(generate_lattice_box({3, 3, 3}, {1, 1, 1}));
  size_t pinched = 0;
  fuzz(c, 1000, 2026, &pinched);
  RecordProperty("sets_with_pinched_edges", static_cast<int>(pinched));
  std::printf("lattice: %zu of 1000 sets have a surface touching itself (edge or vertex)\n", pinched);
}

TEST(MeshConversion, FuzzRandomBreaksOnAnUnstructuredCube) {
  const ConversionCase c = make_case(cgal_cube());
  size_t pinched = 0;
  fuzz(c, 200, 12, &pinched);
  std::printf("cgal cube (%zu tets): %zu of 200 sets have a surface touching itself (edge or vertex)\n",
              c.mesh.tets.size(), pinched);
}

TEST(MeshConversion, BreakingTwiceIsIgnored) {
  ConversionCase c = make_case(generate_lattice_box({1, 1, 1}, {1, 1, 1}));
  MeshConversion conv(c.topology());
  EXPECT_TRUE(conv.break_joint(0, 1.0));
  EXPECT_FALSE(conv.break_joint(0, 2.0));
  EXPECT_EQ(conv.broken_joint_count(), 1u);
  EXPECT_EQ(conv.triangle_count(), 12u + 2u);
  EXPECT_EQ(conv.triangle_time().back(), 1.0);
}

}  // namespace
}  // namespace rift
