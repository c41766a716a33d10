#pragma once
// Rank 0's copy of a log that each rank of a split run appends to for the elements it computes (the
// fracture log: a joint across a boundary breaks on every rank that computes it). Rows [0, prefix) were
// written at set-up and are the same on every rank. Of the others, each rank sends those it counts (`keep`:
// each logged element counted by one rank), and rank 0 rebuilds the log as the prefix followed by every
// rank's rows in the order `before` gives, the order one process writes. Other ranks' logs are not changed.
#include <mpi.h>

#include <cstddef>
#include <functional>

#include "engine/core/table.hpp"

namespace rift {

// Collective. `before(log, a, b)`: row a comes before row b (a strict weak order on the rebuilt rows);
// rows it does not order keep rank order, then their order on their rank. Throws Error (on every rank,
// before any message) when the log is shorter than the prefix, or when the rows would exceed 2 GiB.
void gather_log_to_root(MPI_Comm comm, Table& log, size_t prefix, const std::function<bool(size_t)>& keep,
                        const std::function<bool(const Table&, size_t, size_t)>& before);

}  // namespace rift
