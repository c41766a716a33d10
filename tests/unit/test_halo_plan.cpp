// The owner-computes plan (engine/mesh/halo_plan.hpp): on the FEMDEM mesh of a Kuhn lattice cut by a plane,
// whose ghosts are known in closed form, and on random parts of continuous and jointed meshes, against a
// direct count with sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "engine/core/error.hpp"
#include "engine/mesh/discontinuous_mesh.hpp"
#include "engine/mesh/halo_plan.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "systems/solid_partition_work.hpp"

namespace rift {
namespace {

std::span<const int32_t> flat(const auto& rows) {
  return {rows.empty() ? nullptr : rows.front().data(),
          rows.size() * (rows.empty() ? 0 : rows.front().size())};
}

std::vector<ElementNodes> solid_sets(const DiscontinuousMesh& dm) {
  return {{"tets", 4, flat(dm.tets)}, {"joints", 6, flat(dm.joints)}};
}

// The part of each tet by its centroid's x: the plane x = 1/2 of the unit box.
std::vector<int32_t> halves(const TetMesh& mesh) {
  std::vector<int32_t> part(mesh.tets.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    double x = 0.0;
    for (int32_t v : mesh.tets[t]) x += 0.25 * mesh.nodes[size_t(v)][0];
    part[t] = x < 0.5 ? 0 : 1;
  }
  return part;
}

TEST(HaloPlan, AJointedLatticeCutByAPlaneExchangesTheFacesOfItsCutJoints) {
  // Every tet has its own nodes, so only joints cross the plane: its 2 n^2 faces. Each part computes
  // those joints too and reads the 3 nodes of the other side's face of each: 6 n^2 ghost nodes (a tet
  // has at most one face on a plane, so no node is counted twice). No tet is computed twice.
  const int n = 6;
  const TetMesh mesh = generate_lattice_box({n, n, n}, {1.0, 1.0, 1.0});
  const DiscontinuousMesh dm = make_discontinuous(mesh, [](size_t) { return true; });
  const auto sets = solid_sets(dm);
  const HaloPlan plan = plan_halo(2, halves(mesh), int32_t(dm.nodes.size()), sets);
  ASSERT_EQ(plan.parts.size(), 2u);
  EXPECT_EQ(plan.element_sets, (std::vector<std::string>{"tets", "joints"}));
  for (const PartHalo& p : plan.parts) {
    EXPECT_EQ(p.owned_nodes, int64_t(dm.nodes.size()) / 2);
    EXPECT_EQ(p.computed[0], int64_t(mesh.tets.size()) / 2);
    EXPECT_EQ(p.shared[0], 0);
    EXPECT_EQ(p.shared[1], 2 * n * n);
    EXPECT_EQ(p.ghost_nodes, 6 * n * n);
    EXPECT_EQ(p.nodes_sent, 6 * n * n);
    EXPECT_EQ(p.receives_from, 1);
    EXPECT_EQ(p.sends_to, 1);
  }
  EXPECT_EQ(plan.parts[0].computed[1] + plan.parts[1].computed[1], int64_t(dm.joints.size()) + 2 * n * n);
}

TEST(HaloPlan, OnePartComputesEverythingAndReadsNothing) {
  const TetMesh mesh = generate_lattice_box({3, 3, 3}, {1.0, 1.0, 1.0});
  const DiscontinuousMesh dm = make_discontinuous(mesh, [](size_t t) { return t % 2 == 0; });
  const auto sets = solid_sets(dm);
  const HaloPlan plan =
      plan_halo(1, std::vector<int32_t>(mesh.tets.size(), 0), int32_t(dm.nodes.size()), sets);
  const PartHalo& p = plan.parts[0];
  EXPECT_EQ(p.owned_nodes, int64_t(dm.nodes.size()));
  EXPECT_EQ(p.computed[0], int64_t(dm.tets.size()));
  EXPECT_EQ(p.computed[1], int64_t(dm.joints.size()));
  EXPECT_EQ(p.ghost_nodes + p.nodes_sent + p.receives_from + p.sends_to + p.shared[0] + p.shared[1], 0);
}

// A direct count: the owner of a node is the part of the first tet holding it, or, in units, the part
// most of its unit's nodes have by that rule; a part computes the elements with an own node; its ghosts are
// the other nodes of those elements.
void expect_direct_count(const std::vector<ElementNodes>& sets, int32_t nodes, int32_t parts,
                         const std::vector<int32_t>& tet_part, const std::vector<int32_t>& units) {
  std::vector<int32_t> owner(size_t(nodes), -1);
  for (size_t t = 0; t < tet_part.size(); ++t)
    for (int c = 0; c < 4; ++c)
      if (owner[size_t(sets[0].nodes[4 * t + size_t(c)])] < 0)
        owner[size_t(sets[0].nodes[4 * t + size_t(c)])] = tet_part[t];
  const std::vector<int32_t> by_tets = owner;
  for (size_t u = 0; u < units.size(); ++u) {  // a unit goes to the part most of its nodes are in
    const int32_t end = u + 1 < units.size() ? units[u + 1] : nodes;
    std::map<int32_t, int> count;
    for (int32_t n = units[u]; n < end; ++n) ++count[by_tets[size_t(n)]];
    int32_t best = 0;
    int most = 0;
    for (const auto& [part, c] : count)  // ascending parts: the lowest wins a tie
      if (c > most) {
        best = part;
        most = c;
      }
    for (int32_t n = units[u]; n < end; ++n) owner[size_t(n)] = best;
  }
  auto ghosts = std::vector<std::set<int32_t>>(size_t(parts));
  std::vector<std::vector<int64_t>> computed(size_t(parts), std::vector<int64_t>(sets.size(), 0));
  std::map<std::pair<int32_t, int32_t>, int64_t> link_nodes;  // (reader, owner) -> nodes
  for (size_t s = 0; s < sets.size(); ++s)
    for (size_t e = 0; e < sets[s].nodes.size() / size_t(sets[s].width); ++e) {
      std::set<int32_t> by;
      for (int c = 0; c < sets[s].width; ++c)
        by.insert(owner[size_t(sets[s].nodes[e * size_t(sets[s].width) + size_t(c)])]);
      for (int32_t r : by) {
        ++computed[size_t(r)][s];
        for (int c = 0; c < sets[s].width; ++c) {
          const int32_t v = sets[s].nodes[e * size_t(sets[s].width) + size_t(c)];
          if (owner[size_t(v)] != r) ghosts[size_t(r)].insert(v);
        }
      }
    }
  for (int32_t r = 0; r < parts; ++r)
    for (int32_t v : ghosts[size_t(r)]) ++link_nodes[{r, owner[size_t(v)]}];
  const HaloPlan plan = plan_halo(parts, tet_part, nodes, sets, units);
  for (int32_t r = 0; r < parts; ++r) {
    const PartHalo& p = plan.parts[size_t(r)];
    EXPECT_EQ(p.owned_nodes, std::count(owner.begin(), owner.end(), r)) << "part " << r;
    EXPECT_EQ(p.ghost_nodes, int64_t(ghosts[size_t(r)].size())) << "part " << r;
    EXPECT_EQ(p.computed, computed[size_t(r)]) << "part " << r;
    int32_t from = 0, to = 0;
    int64_t sent = 0;
    for (const auto& [link, count] : link_nodes) {
      from += link.first == r;
      to += link.second == r;
      if (link.second == r) sent += count;
    }
    EXPECT_EQ(p.receives_from, from) << "part " << r;
    EXPECT_EQ(p.sends_to, to) << "part " << r;
    EXPECT_EQ(p.nodes_sent, sent) << "part " << r;
  }
}

// check(sets, nodes, parts, tet_part, units) on random parts of a lattice's FEMDEM mesh with no joints
// (shared nodes), with every tet jointed, and with a third of them; each node alone, then in units of
// random lengths (1-9 nodes).
template <class Check>
void for_random_parts(uint32_t seed, std::initializer_list<int32_t> part_counts, Check&& check) {
  const TetMesh mesh = generate_lattice_box({4, 3, 5}, {1.0, 1.0, 1.0});
  std::mt19937 rng(seed);
  for (int zone_every : {0, 1, 3}) {
    const DiscontinuousMesh dm =
        make_discontinuous(mesh, [&](size_t t) { return zone_every > 0 && t % size_t(zone_every) == 0; });
    for (int32_t parts : part_counts) {
      std::vector<int32_t> tet_part(mesh.tets.size());
      for (int32_t& p : tet_part) p = int32_t(rng() % uint32_t(parts));
      SCOPED_TRACE(testing::Message() << "zone every " << zone_every << ", " << parts << " parts");
      const int32_t nodes = int32_t(dm.nodes.size());
      check(solid_sets(dm), nodes, parts, tet_part, std::vector<int32_t>{});
      std::vector<int32_t> units;
      for (int32_t n = 0; n < nodes; n += 1 + int32_t(rng() % 9)) units.push_back(n);
      SCOPED_TRACE("in units");
      check(solid_sets(dm), nodes, parts, tet_part, units);
    }
  }
}

TEST(HaloPlan, RandomPartsOfContinuousAndJointedMeshesMatchADirectCount) {
  for_random_parts(7, {2, 3, 7}, expect_direct_count);
}

// Each rank's lists against the counts of the whole plan, and what a rank receives from a neighbour
// against what that neighbour sends it.
void expect_rank_lists_match(const std::vector<ElementNodes>& sets, int32_t nodes, int32_t parts,
                             const std::vector<int32_t>& tet_part, const std::vector<int32_t>& units) {
  const HaloPlan plan = plan_halo(parts, tet_part, nodes, sets, units);
  std::vector<RankHalo> ranks;
  for (int32_t r = 0; r < parts; ++r) ranks.push_back(rank_halo(r, parts, tet_part, nodes, sets, units));
  int64_t owned = 0;
  for (int32_t r = 0; r < parts; ++r) {
    const RankHalo& h = ranks[size_t(r)];
    const PartHalo& p = plan.parts[size_t(r)];
    owned += int64_t(h.owned.size());
    EXPECT_EQ(int64_t(h.owned.size()), p.owned_nodes);
    EXPECT_TRUE(std::is_sorted(h.owned.begin(), h.owned.end()));
    EXPECT_EQ(int32_t(h.neighbours.size()), p.receives_from);
    EXPECT_EQ(int32_t(h.neighbours.size()), p.sends_to);
    int64_t received = 0, sent = 0;
    for (size_t k = 0; k < h.neighbours.size(); ++k) {
      received += int64_t(h.receive[k].size());
      sent += int64_t(h.send[k].size());
      const RankHalo& other = ranks[size_t(h.neighbours[k])];
      const auto back = std::find(other.neighbours.begin(), other.neighbours.end(), r);
      ASSERT_NE(back, other.neighbours.end()) << r << " and " << h.neighbours[k];
      EXPECT_EQ(h.receive[k], other.send[size_t(back - other.neighbours.begin())]);
    }
    EXPECT_EQ(received, p.ghost_nodes);
    EXPECT_EQ(sent, p.nodes_sent);
    for (size_t s = 0; s < sets.size(); ++s) EXPECT_EQ(int64_t(h.elements[s].size()), p.computed[s]);
  }
  EXPECT_EQ(owned, nodes);
}

TEST(HaloPlan, EachRanksListsAgreeWithThePlanAndWithTheirNeighbours) {
  for_random_parts(11, {1, 2, 5}, expect_rank_lists_match);
}

TEST(HaloPlan, TheSolidWeighsATetByItselfAndHalfOfEachOfItsJoints) {
  // A jointed tet weighs 2 units for itself and 1 for each of its faces that carries a joint: 6 inside
  // the lattice, less on its boundary; a tet outside the zone weighs 2.
  const int n = 4;
  const TetMesh mesh = generate_lattice_box({n, n, n}, {1.0, 1.0, 1.0});
  const DiscontinuousMesh dm = make_discontinuous(mesh, [](size_t) { return true; });
  const PartitionWork work =
      solid_partition_work(flat(dm.tets), dm.node_vertex, flat(dm.joints), flat(dm.joint_tets));
  ASSERT_EQ(work.tet_weight.size(), mesh.tets.size());
  const size_t boundary_faces = 6 * n * n * 2;
  int64_t total = 0;
  for (int32_t w : work.tet_weight) {
    EXPECT_GE(w, 2 + 1);  // every tet of the lattice has at least one interior face
    EXPECT_LE(w, 2 + 4);
    total += w;
  }
  EXPECT_EQ(total, int64_t(2 * mesh.tets.size() + (4 * mesh.tets.size() - boundary_faces)));
  EXPECT_EQ(work.node_bytes, 48);
  ASSERT_EQ(work.elements.size(), 2u);
  EXPECT_EQ(work.elements[1].weight, 2);
  // The partitioner sees the continuous mesh: the lattice's own tets.
  EXPECT_EQ(work.graph_tets, mesh.tets);
  EXPECT_EQ(work.nodes, int32_t(dm.nodes.size()));
  const PartitionWork dry = solid_partition_work(flat(dm.tets), dm.node_vertex, {}, {});
  EXPECT_EQ(dry.elements.size(), 1u);
  for (int32_t w : dry.tet_weight) EXPECT_EQ(w, 2);
}

TEST(HaloPlan, ANodeInNoTetOrAnIndexOutOfRangeIsRefused) {
  const TetMesh mesh = generate_lattice_box({1, 1, 1}, {1.0, 1.0, 1.0});
  const DiscontinuousMesh dm = make_discontinuous(mesh, [](size_t) { return true; });
  const auto sets = solid_sets(dm);
  const auto nodes = int32_t(dm.nodes.size());
  const std::vector<int32_t> zeros(mesh.tets.size(), 0);
  EXPECT_THROW(plan_halo(1, zeros, nodes + 1, sets), Error);                   // one node in no tet
  EXPECT_THROW(plan_halo(1, zeros, nodes - 1, sets), Error);                   // a node id beyond the count
  EXPECT_THROW(plan_halo(1, std::vector<int32_t>(3, 0), nodes, sets), Error);  // parts for 3 tets of 6
  std::vector<int32_t> beyond = zeros;
  beyond[2] = 1;
  EXPECT_THROW(plan_halo(1, beyond, nodes, sets), Error);  // a part beyond the count
  const std::vector<int32_t> late{1}, unsorted{0, 5, 3}, past{0, nodes};
  EXPECT_THROW(plan_halo(1, zeros, nodes, sets, late), Error);      // units that leave node 0 out
  EXPECT_THROW(plan_halo(1, zeros, nodes, sets, unsorted), Error);  // units out of order
  EXPECT_THROW(plan_halo(1, zeros, nodes, sets, past), Error);      // a unit beyond the nodes
}

}  // namespace
}  // namespace rift
