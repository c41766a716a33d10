// A run split between the ranks of an MPI job (docs/distributed.md): every rank builds the whole world,
// partitions each model's mesh with METIS (seeded: every rank finds the same parts, which is checked), and
// hands each model its rank's share; rank 0 alone writes files, after the models have gathered their rows
// to it; what the ranks must decide alike (a stop, the wall clock, a signal) is agreed.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"
#include "engine/core/state_hash.hpp"
#include "engine/distributed/job_agreement.hpp"
#include "engine/distributed/mpi_runtime.hpp"
#include "engine/distributed/split_run.hpp"
#include "engine/mesh/tet_partition.hpp"
#include "engine/run_loop.hpp"

namespace rift {
namespace {

// Every rank partitions the same mesh itself; the exchange's lists rely on their agreeing.
void check_ranks_agree(const std::vector<int32_t>& part, const std::string& domain) {
  uint64_t hash = fnv1a64(part.data(), part.size() * sizeof(int32_t), fnv1a64_basis);
  uint64_t low = 0, high = 0;
  MPI_Allreduce(&hash, &low, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&hash, &high, 1, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
  if (low != high)
    throw JobError("split run: the ranks partitioned the " + domain +
                   " differently (METIS gave different parts for the same mesh); run on one process");
}

}  // namespace

void RunLoop::split_between_ranks() {
  SplitJob job{MPI_COMM_WORLD, job_rank_, job_size_};
  for (const auto& model : world_->models) {
    std::vector<PartitionWork> domains;
    model->partition_work(domains);
    std::vector<SplitDomain> shares;
    for (const PartitionWork& work : domains) {
      if (work.graph_tets.size() < size_t(job_size_))
        throw Error(
            fmt::format("split run: a job of {} ranks cannot split the {}'s {} tets (each rank needs "
                        "one at least): run it with at most {} ranks",
                        job_size_, work.domain, work.graph_tets.size(), work.graph_tets.size()));
      const TetPartition partition = partition_tets(work.graph_tets, job_size_, work.tet_weight);
      check_ranks_agree(partition.part, work.domain);
      SplitDomain d;
      d.node_owner = node_owners(job_size_, partition.part, work.nodes, work.elements, work.node_units);
      d.share = rank_halo(job_rank_, job_size_, partition.part, work.nodes, work.elements, work.node_units);
      int64_t ghosts = 0;
      for (const auto& list : d.share.receive) ghosts += int64_t(list.size());
      int64_t most_ghosts = ghosts, owned = int64_t(d.share.owned.size()), most_owned = owned;
      MPI_Allreduce(MPI_IN_PLACE, &most_ghosts, 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
      MPI_Allreduce(MPI_IN_PLACE, &most_owned, 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
      spdlog::info(
          "split: the {} ({} tets, {} nodes) into {} ranks by METIS: edge cut {} faces, tet weight imbalance "
          "{:.3f}; nodes owned at most {} a rank (mean {:.0f}), ghosts at most {}",
          work.domain, work.graph_tets.size(), work.nodes, job_size_, partition.edge_cut, partition.imbalance,
          most_owned, double(work.nodes) / job_size_, most_ghosts);
      partition_summary_[work.domain] = {{"ranks", job_size_},
                                         {"tets", work.graph_tets.size()},
                                         {"nodes", work.nodes},
                                         {"edge_cut", partition.edge_cut},
                                         {"weight_imbalance", partition.imbalance},
                                         {"owned_nodes_max", most_owned},
                                         {"ghost_nodes_max", most_ghosts}};
      shares.push_back(std::move(d));
    }
    model->take_share(job, shares);
  }
}

void RunLoop::gather_to_root() {
  if (!split()) return;
  for (const auto& model : world_->models) model->gather_to_root();
}

std::optional<std::string> RunLoop::agree_on_stop(const std::optional<std::string>& mine) const {
  if (!split()) return mine;
  return first_problem(MPI_COMM_WORLD, mine);
}

uint64_t RunLoop::run_state_hash() {
  gather_to_root();
  uint64_t hash = state_hash(world_->store);
  if (split()) MPI_Bcast(&hash, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  return hash;
}

unsigned RunLoop::agree_with_rank_zero(unsigned flags) const {
  return split() ? rank_zero_decides(MPI_COMM_WORLD, flags) : flags;
}

}  // namespace rift
