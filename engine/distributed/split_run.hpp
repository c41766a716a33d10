#pragma once
// What a model is given when a run is split between the processes of an MPI job (Model::take_share): the
// job, and for each of the model's domains (Model::partition_work, in its order) this rank's share of the
// owner-computes plan (engine/mesh/halo_plan.hpp) and every node's owner.
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "engine/mesh/halo_plan.hpp"

namespace rift {

struct SplitJob {
  MPI_Comm comm = MPI_COMM_NULL;
  int32_t rank = 0, size = 1;
};

struct SplitDomain {
  RankHalo share;
  std::vector<int32_t> node_owner;
};

}  // namespace rift
