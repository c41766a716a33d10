// Owner computes, in one process (engine/mesh/halo_plan.hpp, SolidModel::compute_only): a run split into
// shares, each a whole copy of the world that computes only its share (the tets and joints with a node of
// its own, the sum units of its own nodes), with its ghosts' positions and velocities copied in from their
// owners after every step, as the exchange between processes brings them. Every node must then move as in
// one process, to the bit, every joint a share computes must hold the same state, and every unit of the
// node pass's energy sums must add the same bits on the share that owns it, while joints break across the
// shares' boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/mesh/halo_plan.hpp"
#include "engine/mesh/tet_partition.hpp"
#include "engine/partition_report.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"
#include "systems/solid_model.hpp"
#include "tests/unit/test_pulled_block_support.hpp"

using namespace rift;

namespace {

// The pulled block (4e7 Pa breaks joints within the steps run), its fracture zone beyond x = 6 mm, so tets
// with nodes of their own and tets sharing nodes both lie on the shares' boundaries.
std::string pulled_block(bool fused) {
  return test::pulled_block(fused, 0.006, 4.0e7);
}

std::unique_ptr<Simulation> simulation(const std::string& yaml, int threads) {
  return test::quiet_simulation(yaml, threads);
}

SolidModel& solid_of(Simulation& sim) {
  for (const auto& model : sim.world().models)
    if (auto* solid = dynamic_cast<SolidModel*>(model.get())) return *solid;
  throw std::runtime_error("no solid model");
}

const NodeIntegrationSystem& node_pass_of(Simulation& sim) {
  return dynamic_cast<const NodeIntegrationSystem&>(*solid_of(sim).node_integration());
}

// Each unit's sums of the step, from the share that owns the unit, against one process's: the books a
// split run adds over its ranks are then one process's. Returns the units checked.
size_t expect_unit_sums_match(Simulation& one, std::vector<std::unique_ptr<Simulation>>& shares,
                              const std::vector<RankHalo>& halos, int step) {
  const std::span<const kernels::NodeStepResult> all = node_pass_of(one).unit_sums();
  const std::vector<int32_t> first = node_pass_of(one).sum_units();
  size_t checked = 0;
  for (size_t r = 0; r < shares.size(); ++r) {
    const std::span<const kernels::NodeStepResult> mine = node_pass_of(*shares[r]).unit_sums();
    for (size_t u = 0; u < first.size(); ++u) {
      if (!std::binary_search(halos[r].owned.begin(), halos[r].owned.end(), first[u])) continue;
      ++checked;
      EXPECT_EQ(std::memcmp(all[u].work, mine[u].work, sizeof all[u].work), 0)
          << "unit " << u << " step " << step;
      EXPECT_EQ(std::memcmp(&all[u].damping, &mine[u].damping, sizeof(double)), 0) << "unit " << u;
      EXPECT_EQ(all[u].non_finite, mine[u].non_finite);
    }
  }
  return checked;
}

std::span<double> column(Simulation& sim, const char* table, const char* name) {
  return sim.world().store.table(table).span<double>(name);
}

// Bitwise: -0.0 and 0.0 differ, NaNs with the same bits agree.
bool same_bits(std::span<const double> a, std::span<const double> b, size_t row, size_t width) {
  return std::memcmp(a.data() + row * width, b.data() + row * width, width * sizeof(double)) == 0;
}

void run_split(bool fused, int32_t parts, int threads) {
  SCOPED_TRACE(testing::Message() << (fused ? "fused" : "separate") << " passes, " << parts << " shares, "
                                  << threads << " threads each");
  auto one = simulation(pulled_block(fused), 1);
  const std::vector<PartitionWork> domains = collect_partition_work(one->world());
  ASSERT_EQ(domains.size(), 1u);
  const PartitionWork& work = domains[0];
  const TetPartition partition = partition_tets(work.graph_tets, parts, work.tet_weight);
  std::vector<std::unique_ptr<Simulation>> shares;
  std::vector<RankHalo> halos;
  for (int32_t r = 0; r < parts; ++r) {
    halos.push_back(rank_halo(r, parts, partition.part, work.nodes, work.elements, work.node_units));
    ASSERT_FALSE(halos.back().neighbours.empty()) << "share " << r << " has no boundary to test";
    shares.push_back(simulation(pulled_block(fused), threads));
    solid_of(*shares.back()).compute_only(halos.back());
  }
  const char* node_table = "solid_node";
  for (int step = 0; step < 500; ++step) {
    one->step_once();
    for (auto& s : shares) s->step_once();
    if (step % 50 == 49) {  // every unit has one owner, whose sums are one process's
      ASSERT_EQ(expect_unit_sums_match(*one, shares, halos, step), node_pass_of(*one).sum_units().size());
    }
    // The exchange: each share's ghosts from their owners.
    for (int32_t r = 0; r < parts; ++r)
      for (size_t k = 0; k < halos[size_t(r)].neighbours.size(); ++k) {
        Simulation& from = *shares[size_t(halos[size_t(r)].neighbours[k])];
        for (const char* name : {"x", "v"}) {
          const auto src = column(from, node_table, name);
          const auto dst = column(*shares[size_t(r)], node_table, name);
          for (int32_t n : halos[size_t(r)].receive[k])
            std::memcpy(&dst[3 * size_t(n)], &src[3 * size_t(n)], 3 * sizeof(double));
        }
      }
  }
  ASSERT_GT(one->world().store.table("solid_fracture_event").size(), 0u) << "no joint broke";
  int64_t checked_nodes = 0, checked_joints = 0;
  for (int32_t r = 0; r < parts; ++r) {
    Simulation& share = *shares[size_t(r)];
    for (const char* name : {"x", "v"}) {
      const auto a = column(*one, node_table, name), b = column(share, node_table, name);
      for (int32_t n : halos[size_t(r)].owned)
        ASSERT_TRUE(same_bits(a, b, size_t(n), 3)) << name << " of node " << n << ", share " << r;
    }
    checked_nodes += int64_t(halos[size_t(r)].owned.size());
    const auto d1 = column(*one, "solid_joint", "d_max"), d2 = column(share, "solid_joint", "d_max");
    const auto b1 = one->world().store.table("solid_joint").span<const uint8_t>("broken");
    const auto b2 = share.world().store.table("solid_joint").span<const uint8_t>("broken");
    const size_t width = d1.size() / b1.size();
    for (int32_t j : halos[size_t(r)].elements[1]) {
      ASSERT_TRUE(same_bits(d1, d2, size_t(j), width)) << "damage history of joint " << j << ", share " << r;
      ASSERT_EQ(b1[size_t(j)], b2[size_t(j)]) << "joint " << j << ", share " << r;
    }
    checked_joints += int64_t(halos[size_t(r)].elements[1].size());
  }
  EXPECT_EQ(checked_nodes, int64_t(work.nodes));
  EXPECT_GE(checked_joints, int64_t(one->world().store.table("solid_joint").size()));
}

TEST(SolidShare, SharesMoveEveryNodeAsOneProcessToTheBitWhileJointsBreak) {
  for (bool fused : {true, false})
    for (int32_t parts : {2, 3}) run_split(fused, parts, 1);
  run_split(true, 3, 2);
}

TEST(SolidShare, ASceneWithContactIsRefused) {
  auto sim = simulation(pulled_block(true) + "  contact: {friction: 0.5}\n", 1);
  const std::vector<PartitionWork> domains = collect_partition_work(sim->world());
  const PartitionWork& work = domains[0];
  const TetPartition partition = partition_tets(work.graph_tets, 2, work.tet_weight);
  const RankHalo halo = rank_halo(0, 2, partition.part, work.nodes, work.elements, work.node_units);
  EXPECT_THROW(solid_of(*sim).compute_only(halo), Error);
}

}  // namespace
