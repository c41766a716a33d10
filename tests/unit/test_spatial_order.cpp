// Morton renumbering of a mesh (engine/mesh/spatial_order.hpp): the same mesh afterwards (same tets as
// point sets, same surfaces, positive orientation kept), deterministic, and neighbours close in memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/mesh_quality.hpp"
#include "engine/mesh/spatial_order.hpp"

namespace rift {
namespace {

using Point = std::array<double, 3>;

std::multiset<std::array<Point, 4>> tets_as_points(const TetMesh& m) {
  std::multiset<std::array<Point, 4>> out;
  for (const auto& t : m.tets) {
    std::array<Point, 4> p{m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]};
    std::sort(p.begin(), p.end());
    out.insert(p);
  }
  return out;
}

// Mean |a - b| over pairs of tets that share a face: how far apart neighbours sit in the tet table.
double mean_neighbour_distance(const TetMesh& m) {
  std::map<std::array<int32_t, 3>, size_t> first;
  double sum = 0;
  size_t pairs = 0;
  for (size_t e = 0; e < m.tets.size(); ++e)
    for (int f = 0; f < 4; ++f) {
      std::array<int32_t, 3> k{m.tets[e][(f + 1) % 4], m.tets[e][(f + 2) % 4], m.tets[e][(f + 3) % 4]};
      std::sort(k.begin(), k.end());
      const auto [it, inserted] = first.emplace(k, e);
      if (!inserted) sum += double(e - it->second), ++pairs;
    }
  return sum / double(pairs);
}

// A lattice with its vertices and tets shuffled: a mesh in no useful order.
TetMesh shuffled_lattice() {
  TetMesh m = generate_lattice_box({12, 12, 12}, {1, 1, 1});
  std::mt19937_64 rng(3);
  std::vector<int32_t> perm(m.nodes.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<Point> nodes(m.nodes.size());
  for (size_t v = 0; v < perm.size(); ++v) nodes[perm[v]] = m.nodes[v];
  m.nodes = nodes;
  for (auto& t : m.tets)
    for (int32_t& v : t) v = perm[v];
  for (auto& t : m.triangles)
    for (int32_t& v : t) v = perm[v];
  std::shuffle(m.tets.begin(), m.tets.end(), rng);
  return m;
}

TEST(SpatialOrder, SameMeshNeighboursCloseInMemory) {
  const TetMesh before = shuffled_lattice();
  TetMesh after = before;
  order_along_curve(after);
  EXPECT_EQ(tets_as_points(after), tets_as_points(before));
  const MeshQuality q = measure_quality(after);
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_NEAR(q.volume, 1.0, 1e-12);
  ASSERT_EQ(after.triangles.size(), before.triangles.size());
  for (size_t t = 0; t < after.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      EXPECT_EQ(after.nodes[after.triangles[t][i]], before.nodes[before.triangles[t][i]]);
  const double shuffled = mean_neighbour_distance(before), ordered = mean_neighbour_distance(after);
  std::printf("mean index distance of face neighbours: shuffled %.0f, Morton %.0f (of %zu tets)\n", shuffled,
              ordered, after.tets.size());
  EXPECT_LT(ordered, 0.1 * shuffled);

  TetMesh again = before;
  order_along_curve(again);
  EXPECT_EQ(again.tets, after.tets);
  EXPECT_EQ(again.nodes, after.nodes);
}

}  // namespace
}  // namespace rift
