#pragma once
// Rank 0's copy of a split run's store, for what only rank 0 writes: outputs, checkpoints and the state
// hash. Every rank keeps the whole store (docs/distributed.md, "Order of the work", step 1), but a row is
// up to date only on the ranks that compute it; the one that counts it (a node's owner, an element's
// first node's owner: engine/mesh/halo_plan.hpp) holds the values one process would. to_root() sends
// every such row of every column of the listed tables to rank 0, one message per rank, so that rank 0's
// store equals one process's. Tables not listed are the same on every rank (set-up data, totals reduced
// over the ranks) or are merged by a rule of their own (the fracture log, by step and joint).
//
// The rows of a listed table are fixed: its row count is checked against the owners at every gather.
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/table.hpp"

namespace rift {

struct RowOwners {
  std::string table;
  std::vector<int32_t> owner;  // per row: the rank whose values are the run's
};

class StoreGather {
 public:
  // Throws Error when an owner is not a rank of `comm`. The communicator is duplicated, so the gather's
  // messages never meet other traffic.
  StoreGather(MPI_Comm comm, std::vector<RowOwners> tables);
  ~StoreGather();
  StoreGather(const StoreGather&) = delete;
  StoreGather& operator=(const StoreGather&) = delete;

  // Collective. Rank 0 receives every other rank's rows; the other ranks' stores are not changed. Throws
  // Error (on every rank, before any message) when a listed table is missing or its row count differs
  // from its owners', or when one rank would send more than 2 GiB.
  void to_root(Store& store);

  int32_t rank() const { return rank_; }
  int64_t bytes_received() const { return bytes_received_; }  // rank 0, by the last gather

 private:
  struct Listed {
    std::string table;
    std::vector<int32_t> owner;
    std::vector<std::vector<int32_t>> rows;  // per rank, ascending (rank 0's are never sent)
  };
  int64_t bytes_from(int32_t rank, const Store& store) const;

  MPI_Comm comm_ = MPI_COMM_NULL;
  int32_t rank_ = 0, size_ = 1;
  std::vector<Listed> tables_;
  std::vector<std::byte> buffer_;
  int64_t bytes_received_ = 0;
};

}  // namespace rift
