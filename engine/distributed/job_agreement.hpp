#pragma once
// Decisions every rank of a split run must take alike, or the others would wait for it forever in the next
// exchange: whether the run stops (a guard's diagnosis on any rank stops all of them, with the diagnosis
// of the lowest rank that has one), and what only one rank can know (the wall clock, a signal), which
// rank 0 decides for all.
#include <mpi.h>

#include <optional>
#include <string>

#include "engine/core/error.hpp"

namespace rift {

// An error every rank of the job raised alike, at the same point: the run ends on every rank without
// MPI_Abort, and rank 0 reports it. Any other error in a split run is one rank's and ends the job.
class JobError : public Error {
 public:
  using Error::Error;
};

// Collective. The diagnosis of the lowest rank with one (`mine`, empty for none), on every rank; nullopt
// when no rank has one.
std::optional<std::string> first_problem(MPI_Comm comm, const std::optional<std::string>& mine);

// Collective. Rank 0's flags, on every rank.
unsigned rank_zero_decides(MPI_Comm comm, unsigned flags);

}  // namespace rift
