#include "engine/distributed/share_reduction.hpp"

#include <vector>

namespace rift {

ShareReduction::ShareReduction(MPI_Comm comm) {
  MPI_Comm_dup(comm, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

ShareReduction::~ShareReduction() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

void ShareReduction::max(std::span<double> values) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MAX, comm_);
}

void ShareReduction::sum(std::span<int64_t> values) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_INT64_T, MPI_SUM, comm_);
}

void ShareReduction::min(std::span<int64_t> values) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_INT64_T, MPI_MIN, comm_);
}

// The two grid sums are multiples of their grids' quanta below 2^53 quanta whatever the split (the grid's
// bound counts every term of every rank), so MPI's additions, in whatever order, are exact.
void ShareReduction::sum(std::span<kernels::ReproducibleSum> sums) const {
  if (size_ == 1) return;
  std::vector<double> sides(2 * sums.size());
  std::vector<int64_t> exceeded(sums.size());
  for (size_t i = 0; i < sums.size(); ++i) {
    sides[2 * i] = sums[i].first, sides[2 * i + 1] = sums[i].second;
    exceeded[i] = sums[i].exceeded;
  }
  MPI_Allreduce(MPI_IN_PLACE, sides.data(), int(sides.size()), MPI_DOUBLE, MPI_SUM, comm_);
  MPI_Allreduce(MPI_IN_PLACE, exceeded.data(), int(exceeded.size()), MPI_INT64_T, MPI_SUM, comm_);
  for (size_t i = 0; i < sums.size(); ++i) {
    sums[i].first = sides[2 * i], sums[i].second = sides[2 * i + 1];
    sums[i].exceeded = exceeded[i];
  }
}

}  // namespace rift
