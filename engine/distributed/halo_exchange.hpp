#pragma once
// The exchange a rank's ghosts need each step (engine/mesh/halo_plan.hpp, RankHalo): the rows of state of
// the nodes it reads from its neighbours arrive in the same global rows as one process keeps them, and the
// rows of its own nodes that they read leave. Non-blocking: begin() packs and posts the receives and
// sends, finish() waits for them and unpacks, so work on the elements that read no ghost can run between
// the two. The buffers are sized once; no exchange allocates.
//
// The exchange runs on a duplicate of the communicator, so its messages never meet other traffic, and
// keeps MPI's default error handler: an MPI error, or a rank that dies, ends every rank of the job with
// MPI's message instead of leaving the others waiting.
#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/halo_plan.hpp"

namespace rift {

class HaloExchange {
 public:
  // width: doubles per node row (6 for a position and a velocity). The halo's lists are copied.
  HaloExchange(MPI_Comm comm, const RankHalo& halo, int32_t width);
  ~HaloExchange();
  HaloExchange(const HaloExchange&) = delete;
  HaloExchange& operator=(const HaloExchange&) = delete;

  // rows: `width` doubles per node, in global node order; begin() reads the own nodes' rows that the
  // neighbours read, finish() writes the ghosts' rows and nothing else. Throws Error when rows is too short
  // for the halo's nodes, or when finish() has no begin() before it.
  void begin(std::span<const double> rows);
  void finish(std::span<double> rows);

  int32_t neighbours() const { return int32_t(neighbours_.size()); }
  int64_t doubles_sent() const { return int64_t(send_buffer_.size()); }
  int64_t doubles_received() const { return int64_t(receive_buffer_.size()); }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int32_t width_ = 0;
  std::vector<int32_t> neighbours_;
  std::vector<int32_t> send_nodes_, receive_nodes_;  // all neighbours' lists, one after the other
  std::vector<int64_t> send_start_, receive_start_;  // per neighbour, in nodes, and the end
  std::vector<double> send_buffer_, receive_buffer_;
  std::vector<MPI_Request> requests_;
  int32_t highest_node_ = -1;
  bool in_flight_ = false;
};

}  // namespace rift
