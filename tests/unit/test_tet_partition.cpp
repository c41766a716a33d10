// METIS partitions of a tet mesh (engine/mesh/tet_partition.hpp), on Kuhn lattices whose best cuts are
// known: a box of n^3 cubes (6 tets each, 2 triangles on each cube face) cut by a plane between two layers
// of cubes has 2 n^2 shared faces across it.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "engine/core/error.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/tet_partition.hpp"

namespace rift {
namespace {

TEST(TetPartition, TheDualGraphHasEveryInteriorFaceOnceFromEachSide) {
  const TetMesh mesh = generate_lattice_box({4, 4, 4}, {1.0, 1.0, 1.0});
  const TetDualGraph g = tet_dual_graph(mesh);
  ASSERT_EQ(g.start.size(), mesh.tets.size() + 1);
  // Faces: 4 per tet, each interior one shared by two, each boundary one (2 per cube face on the box's
  // surface: 6 faces x 16 cube faces x 2) by one.
  const size_t boundary = 6 * 16 * 2, interior = (4 * mesh.tets.size() - boundary) / 2;
  EXPECT_EQ(g.adjacency.size(), 2 * interior);
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    for (int32_t k = g.start[t]; k < g.start[t + 1]; ++k) {
      const auto o = size_t(g.adjacency[size_t(k)]);
      const auto back = g.adjacency.begin() + g.start[o];
      EXPECT_NE(std::find(back, g.adjacency.begin() + g.start[o + 1], int32_t(t)),
                g.adjacency.begin() + g.start[o + 1])
          << "tet " << t << " lists " << o << " but not the reverse";
    }
}

TEST(TetPartition, PartsAreBalancedAndTheirCutIsNearThePlanesCut) {
  const int n = 10;
  const TetMesh mesh = generate_lattice_box({n, n, n}, {1.0, 1.0, 1.0});
  for (int32_t parts : {2, 3, 8}) {
    const TetPartition p = partition_tets(mesh, parts);
    ASSERT_EQ(p.part.size(), mesh.tets.size());
    std::set<int32_t> seen(p.part.begin(), p.part.end());
    EXPECT_EQ(seen.size(), size_t(parts));
    EXPECT_GE(*seen.begin(), 0);
    EXPECT_LT(*seen.rbegin(), parts);
    // METIS's default load imbalance for k-way is 1.03; 1.05 leaves room for its coarsening's rounding.
    EXPECT_LE(p.imbalance, 1.05) << parts << " parts";
    // Two parts: the best cut is one plane, 2 n^2 = 200 faces; a multilevel heuristic may not find it,
    // but a cut twice as long would be a poor partition. Eight parts: three planes, 3 x 200.
    if (parts == 2) {
      EXPECT_LE(p.edge_cut, 2 * 2 * n * n);
    }
    if (parts == 8) {
      EXPECT_LE(p.edge_cut, 2 * 3 * 2 * n * n);
    }
    EXPECT_GT(p.edge_cut, 0);
  }
}

TEST(TetPartition, TheSameMeshGivesTheSameParts) {
  const TetMesh mesh = generate_lattice_box({6, 6, 6}, {1.0, 1.0, 1.0});
  EXPECT_EQ(partition_tets(mesh, 4).part, partition_tets(mesh, 4).part);
}

TEST(TetPartition, WeightsBalanceTheWorkNotTheCount) {
  const TetMesh mesh = generate_lattice_box({8, 8, 8}, {1.0, 1.0, 1.0});
  std::vector<int32_t> weight(mesh.tets.size(), 1);
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    double x = 0.0;
    for (int32_t v : mesh.tets[t]) x += 0.25 * mesh.nodes[size_t(v)][0];
    if (x < 0.5) weight[t] = 3;  // the half x < 0.5 carries three times the work
  }
  const TetPartition p = partition_tets(mesh, 2, weight);
  EXPECT_LE(p.imbalance, 1.05);
  int64_t total = 0;
  for (int64_t w : p.part_weight) total += w;
  EXPECT_EQ(total, 3 * int64_t(mesh.tets.size()) / 2 + int64_t(mesh.tets.size()) / 2);
}

TEST(TetPartition, OnePartIsTheWholeMeshAndBadRequestsAreRefused) {
  const TetMesh mesh = generate_lattice_box({2, 2, 2}, {1.0, 1.0, 1.0});
  const TetPartition one = partition_tets(mesh, 1);
  EXPECT_TRUE(std::all_of(one.part.begin(), one.part.end(), [](int32_t p) { return p == 0; }));
  EXPECT_EQ(one.edge_cut, 0);
  EXPECT_DOUBLE_EQ(one.imbalance, 1.0);
  EXPECT_THROW(partition_tets(mesh, 0), Error);
  EXPECT_THROW(partition_tets(mesh, int32_t(mesh.tets.size()) + 1), Error);
  std::vector<int32_t> bad(mesh.tets.size(), 1);
  bad[3] = 0;
  EXPECT_THROW(partition_tets(mesh, 2, bad), Error);
  EXPECT_THROW(partition_tets(mesh, 2, std::vector<int32_t>(5, 1)), Error);
}

}  // namespace
}  // namespace rift
