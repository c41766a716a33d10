// The ghosts' exchange over MPI (engine/distributed/halo_exchange.hpp). Run alone it is one rank with no
// neighbours; tests/CMakeLists.txt runs it again under mpirun on 2 and 3 ranks, where every rank partitions
// the same meshes, exchanges, and checks that exactly its ghosts' rows arrived with their owners' values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/distributed/halo_exchange.hpp"
#include "engine/distributed/mpi_runtime.hpp"
#include "engine/mesh/discontinuous_mesh.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/tet_partition.hpp"

namespace rift {
namespace {

constexpr int32_t kWidth = 6;  // a position and a velocity

double value(int32_t node, int32_t component, int round) {
  return 1000.0 * round + 10.0 * node + component;
}

std::span<const int32_t> flat(const auto& rows) {
  return {rows.front().data(), rows.size() * rows.front().size()};
}

// Every rank computes the parts itself, from the same mesh: they must agree, which the exchange relies on.
void expect_ranks_agree(const std::vector<int32_t>& part) {
  uint64_t hash = 1469598103934665603ull;
  for (int32_t p : part) hash = (hash ^ uint32_t(p)) * 1099511628211ull;
  uint64_t lowest = 0, highest = 0;
  MPI_Allreduce(&hash, &lowest, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&hash, &highest, 1, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(lowest, highest) << "the ranks partitioned the same mesh differently";
}

void exchange_and_check(const TetMesh& mesh, const DiscontinuousMesh& dm) {
  const MpiRank me = mpi_runtime_init();
  const std::vector<int32_t> part = partition_tets(mesh, me.size).part;
  expect_ranks_agree(part);
  std::vector<ElementNodes> sets{{"tets", 4, flat(dm.tets)}};
  if (!dm.joints.empty()) sets.push_back({"joints", 6, flat(dm.joints)});
  const auto nodes = int32_t(dm.nodes.size());
  const RankHalo halo = rank_halo(me.rank, me.size, part, nodes, sets);
  HaloExchange exchange(MPI_COMM_WORLD, halo, kWidth);
  std::vector<uint8_t> kind(size_t(nodes), 0);  // 1 own, 2 ghost
  for (int32_t n : halo.owned) kind[size_t(n)] = 1;
  for (const auto& list : halo.receive)
    for (int32_t n : list) kind[size_t(n)] = 2;
  if (me.size > 1) {
    EXPECT_GT(exchange.neighbours(), 0);
  }
  std::vector<double> rows(size_t(nodes) * kWidth);
  for (int round = 0; round < 3; ++round) {  // values change each round: nothing stale may pass
    for (int32_t n = 0; n < nodes; ++n)
      for (int32_t c = 0; c < kWidth; ++c)
        rows[size_t(n * kWidth + c)] =
            kind[size_t(n)] == 1 ? value(n, c, round) : std::numeric_limits<double>::quiet_NaN();
    exchange.begin(rows);
    exchange.finish(rows);
    for (int32_t n = 0; n < nodes; ++n)
      for (int32_t c = 0; c < kWidth; ++c) {
        const double got = rows[size_t(n * kWidth + c)];
        if (kind[size_t(n)] == 0)
          ASSERT_TRUE(std::isnan(got)) << "rank " << me.rank << " node " << n << ": neither own nor a ghost";
        else
          ASSERT_EQ(got, value(n, c, round)) << "rank " << me.rank << " node " << n << " round " << round;
      }
  }
}

TEST(HaloExchange, AJointedBlocksGhostsReceiveTheirOwnersRows) {
  const TetMesh mesh = generate_lattice_box({5, 4, 6}, {1.0, 1.0, 1.0});
  exchange_and_check(mesh, make_discontinuous(mesh, [](size_t) { return true; }));
}

TEST(HaloExchange, ABlockWithSharedNodesAndAFractureZoneReceivesItsGhostsToo) {
  const TetMesh mesh = generate_lattice_box({5, 4, 6}, {1.0, 1.0, 1.0});
  exchange_and_check(mesh, make_discontinuous(mesh, [](size_t t) { return t % 3 == 0; }));
}

TEST(HaloExchange, RowsTooShortAndAFinishWithoutABeginAreRefused) {
  const MpiRank me = mpi_runtime_init();
  const TetMesh mesh = generate_lattice_box({4, 4, 4}, {1.0, 1.0, 1.0});
  const DiscontinuousMesh dm = make_discontinuous(mesh, [](size_t) { return true; });
  const std::vector<ElementNodes> sets{{"tets", 4, flat(dm.tets)}, {"joints", 6, flat(dm.joints)}};
  const RankHalo halo =
      rank_halo(me.rank, me.size, partition_tets(mesh, me.size).part, int32_t(dm.nodes.size()), sets);
  HaloExchange exchange(MPI_COMM_WORLD, halo, kWidth);
  std::vector<double> rows(dm.nodes.size() * kWidth, 0.0);
  EXPECT_THROW(exchange.finish(rows), Error);
  if (exchange.neighbours() > 0) {
    EXPECT_THROW(exchange.begin(std::span<const double>(rows).first(kWidth)), Error);
  }
  exchange.begin(rows);
  EXPECT_THROW(exchange.begin(rows), Error);
  exchange.finish(rows);
}

}  // namespace
}  // namespace rift
