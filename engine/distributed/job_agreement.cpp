#include "engine/distributed/job_agreement.hpp"

#include <climits>

namespace rift {

std::optional<std::string> first_problem(MPI_Comm comm, const std::optional<std::string>& mine) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int first = mine ? rank : INT_MAX;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == INT_MAX) return std::nullopt;
  std::string message = rank == first ? *mine : std::string();
  int length = int(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(size_t(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  return message;
}

unsigned rank_zero_decides(MPI_Comm comm, unsigned flags) {
  MPI_Bcast(&flags, 1, MPI_UNSIGNED, 0, comm);
  return flags;
}

}  // namespace rift
