#pragma once
// What the ranks of a split run combine after each step's graph, on the thread that calls MPI: the largest
// terms of the order-free energy sums (whose grids must be the same on every rank), then the sums on those
// grids, which add exactly in any order (kernels/reproducible_sum.hpp), and counts. Every rank makes the
// same calls in the same order (they are collective); one process is a job of one, where each call leaves
// its values as they are.
#include <mpi.h>

#include <cstdint>
#include <span>

#include "kernels/reproducible_sum.hpp"

namespace rift {

class ShareReduction {
 public:
  // The communicator is duplicated, so the reductions never meet other traffic.
  explicit ShareReduction(MPI_Comm comm);
  ~ShareReduction();
  ShareReduction(const ShareReduction&) = delete;
  ShareReduction& operator=(const ShareReduction&) = delete;

  // Element-wise over the ranks, in place.
  void max(std::span<double> values) const;
  void sum(std::span<int64_t> values) const;
  void min(std::span<int64_t> values) const;
  // Sums made on grids every rank shares: exact, so the result has the bits of one process's sum.
  void sum(std::span<kernels::ReproducibleSum> sums) const;

  int32_t rank() const { return rank_; }
  int32_t size() const { return size_; }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int32_t rank_ = 0, size_ = 1;
};

}  // namespace rift
