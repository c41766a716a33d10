#include "engine/distributed/halo_exchange.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.hpp"

namespace rift {
namespace {

constexpr int kHaloTag = 1;

// Concatenates per-neighbour lists; start gets each list's first position and the end.
void flatten(const std::vector<std::vector<int32_t>>& lists, std::vector<int32_t>& all,
             std::vector<int64_t>& start) {
  start.assign(1, 0);
  for (const auto& l : lists) {
    all.insert(all.end(), l.begin(), l.end());
    start.push_back(int64_t(all.size()));
  }
}

}  // namespace

HaloExchange::HaloExchange(MPI_Comm comm, const RankHalo& halo, int32_t width)
    : width_(width), neighbours_(halo.neighbours) {
  if (width < 1) throw Error(fmt::format("halo exchange: {} doubles a row", width));
  MPI_Comm_dup(comm, &comm_);
  flatten(halo.send, send_nodes_, send_start_);
  flatten(halo.receive, receive_nodes_, receive_start_);
  for (int32_t n : send_nodes_) highest_node_ = std::max(highest_node_, n);
  for (int32_t n : receive_nodes_) highest_node_ = std::max(highest_node_, n);
  send_buffer_.resize(send_nodes_.size() * size_t(width));
  receive_buffer_.resize(receive_nodes_.size() * size_t(width));
  requests_.resize(2 * neighbours_.size());
}

HaloExchange::~HaloExchange() {
  if (in_flight_) MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

void HaloExchange::begin(std::span<const double> rows) {
  if (int64_t(rows.size()) < (int64_t(highest_node_) + 1) * width_)
    throw Error(fmt::format("halo exchange: {} doubles for node rows up to {} of {} each", rows.size(),
                            highest_node_, width_));
  if (in_flight_) throw Error("halo exchange: begin() twice without finish()");
  for (size_t i = 0; i < send_nodes_.size(); ++i)
    std::copy_n(rows.begin() + int64_t(send_nodes_[i]) * width_, width_,
                send_buffer_.begin() + int64_t(i) * width_);
  for (size_t k = 0; k < neighbours_.size(); ++k) {
    const int64_t r0 = receive_start_[k] * width_, r1 = receive_start_[k + 1] * width_;
    MPI_Irecv(receive_buffer_.data() + r0, int(r1 - r0), MPI_DOUBLE, neighbours_[k], kHaloTag, comm_,
              &requests_[2 * k]);
    const int64_t s0 = send_start_[k] * width_, s1 = send_start_[k + 1] * width_;
    MPI_Isend(send_buffer_.data() + s0, int(s1 - s0), MPI_DOUBLE, neighbours_[k], kHaloTag, comm_,
              &requests_[2 * k + 1]);
  }
  in_flight_ = true;
}

void HaloExchange::finish(std::span<double> rows) {
  if (!in_flight_) throw Error("halo exchange: finish() without begin()");
  if (int64_t(rows.size()) < (int64_t(highest_node_) + 1) * width_)
    throw Error(fmt::format("halo exchange: {} doubles for node rows up to {} of {} each", rows.size(),
                            highest_node_, width_));
  MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  in_flight_ = false;
  for (size_t i = 0; i < receive_nodes_.size(); ++i)
    std::copy_n(receive_buffer_.begin() + int64_t(i) * width_, width_,
                rows.begin() + int64_t(receive_nodes_[i]) * width_);
}

}  // namespace rift
