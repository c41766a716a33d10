// Rank 0's copy of a split run's store (engine/distributed/store_gather.hpp). Run alone it is one rank that
// already holds everything; tests/CMakeLists.txt runs it again under mpirun on 2 and 3 ranks, where every
// rank partitions the same jointed block, keeps true values only in the rows it counts and stale ones
// elsewhere, and rank 0's store after the gather hashes as the true store does.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/core/state_hash.hpp"
#include "engine/distributed/mpi_runtime.hpp"
#include "engine/distributed/store_gather.hpp"
#include "engine/mesh/discontinuous_mesh.hpp"
#include "engine/mesh/halo_plan.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/tet_partition.hpp"

namespace rift {
namespace {

std::span<const int32_t> flat(const auto& rows) {
  return {rows.front().data(), rows.size() * rows.front().size()};
}

// A store shaped like the solid's: nodes (two f64 columns of 3, a u8 flag), tets (their nodes, an f64 of
// 6), joints (an f64, an i32), and a table of totals every rank holds alike. stale: the rank whose stale
// copy this is (its rows it does not count get values no other rank has), or -1 for the true store.
Store make_store(const DiscontinuousMesh& dm, const std::vector<int32_t>& node_owner,
                 const std::vector<int32_t>& tet_owner, const std::vector<int32_t>& joint_owner, int stale) {
  const auto value = [stale](size_t row, int c, int32_t owner) {
    return stale < 0 || owner == stale ? 10.0 * double(row) + c : -1.0 - stale - 1e-3 * double(row);
  };
  Store store;
  Table& nodes = store.add_table("node");
  nodes.add<double>("x", 3), nodes.add<double>("v", 3), nodes.add<uint8_t>("flag");
  nodes.resize(dm.nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) {
    for (int c = 0; c < 3; ++c) {
      nodes.span<double>("x")[3 * n + size_t(c)] = value(n, c, node_owner[n]);
      nodes.span<double>("v")[3 * n + size_t(c)] = -value(n, c, node_owner[n]);
    }
    nodes.span<uint8_t>("flag")[n] = uint8_t(value(n, 0, node_owner[n]) > 0 ? n % 7 : 200);
  }
  Table& tets = store.add_table("tet");
  tets.add<int32_t>("nodes", 4), tets.add<double>("stress", 6);
  tets.resize(dm.tets.size());
  for (size_t t = 0; t < tets.size(); ++t) {
    for (int c = 0; c < 4; ++c) tets.span<int32_t>("nodes")[4 * t + size_t(c)] = dm.tets[t][size_t(c)];
    for (int c = 0; c < 6; ++c) tets.span<double>("stress")[6 * t + size_t(c)] = value(t, c, tet_owner[t]);
  }
  Table& joints = store.add_table("joint");
  joints.add<double>("damage"), joints.add<int32_t>("broken_step");
  joints.resize(dm.joints.size());
  for (size_t j = 0; j < joints.size(); ++j) {
    joints.span<double>("damage")[j] = value(j, 0, joint_owner[j]);
    joints.span<int32_t>("broken_step")[j] = int32_t(value(j, 1, joint_owner[j]));
  }
  Table& totals = store.add_table("totals");
  totals.add<double>("work");
  totals.resize(1);
  totals.span<double>("work")[0] = 42.0;
  return store;
}

struct Split {
  DiscontinuousMesh dm;
  std::vector<int32_t> node_owner, tet_owner, joint_owner;
};

Split split_block(int32_t ranks) {
  const TetMesh mesh = generate_lattice_box({5, 4, 6}, {1.0, 1.0, 1.0});
  Split s{make_discontinuous(mesh, [](size_t t) { return t % 3 != 0; }), {}, {}, {}};
  const std::vector<int32_t> part = partition_tets(mesh, ranks).part;
  const ElementNodes tets{"tets", 4, flat(s.dm.tets)}, joints{"joints", 6, flat(s.dm.joints)};
  const std::vector<ElementNodes> sets{tets, joints};
  s.node_owner = node_owners(ranks, part, int32_t(s.dm.nodes.size()), sets);
  s.tet_owner = element_owners(tets, s.node_owner);
  s.joint_owner = element_owners(joints, s.node_owner);
  return s;
}

TEST(StoreGather, RankZeroHoldsEveryRowAsItsCountingRankHasIt) {
  const MpiRank me = mpi_runtime_init();
  const Split s = split_block(me.size);
  ASSERT_FALSE(s.dm.joints.empty());
  Store truth = make_store(s.dm, s.node_owner, s.tet_owner, s.joint_owner, -1);
  Store mine = make_store(s.dm, s.node_owner, s.tet_owner, s.joint_owner, me.rank);
  const uint64_t before = state_hash(mine);
  if (me.size > 1) {
    EXPECT_NE(before, state_hash(truth)) << "every rank has stale rows to be replaced";
  }
  StoreGather gather(MPI_COMM_WORLD,
                     {{"node", s.node_owner}, {"tet", s.tet_owner}, {"joint", s.joint_owner}});
  for (int round = 0; round < 2; ++round) {  // buffers are reused
    gather.to_root(mine);
    if (me.rank == 0)
      EXPECT_EQ(state_hash(mine), state_hash(truth)) << "round " << round;
    else
      EXPECT_EQ(state_hash(mine), before) << "rank " << me.rank << ": a gather changes rank 0 alone";
  }
  if (me.rank == 0) {
    EXPECT_EQ(gather.bytes_received() > 0, me.size > 1);
  }
}

TEST(StoreGather, ATableThatChangedItsRowsIsRefusedOnEveryRankBeforeAnyMessage) {
  const MpiRank me = mpi_runtime_init();
  const Split s = split_block(me.size);
  Store store = make_store(s.dm, s.node_owner, s.tet_owner, s.joint_owner, me.rank);
  store.table("joint").resize(s.dm.joints.size() - 1);
  StoreGather gather(MPI_COMM_WORLD, {{"node", s.node_owner}, {"joint", s.joint_owner}});
  try {
    gather.to_root(store);
    ADD_FAILURE() << "a gather over a table whose rows changed must throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("joint has"), std::string::npos) << e.what();
  }
  StoreGather missing(MPI_COMM_WORLD, {{"contact", {}}});
  EXPECT_THROW(missing.to_root(store), Error);
}

TEST(StoreGather, AnOwnerOutsideTheJobIsRefused) {
  const MpiRank me = mpi_runtime_init();
  EXPECT_THROW(StoreGather(MPI_COMM_WORLD, {{"node", {0, me.size}}}), Error);
  EXPECT_THROW(StoreGather(MPI_COMM_WORLD, {{"node", {-1}}}), Error);
}

}  // namespace
}  // namespace rift
