#include "engine/distributed/store_gather.hpp"

#include <fmt/format.h>

#include <climits>
#include <cstring>

#include "engine/core/error.hpp"

namespace rift {
namespace {

size_t row_bytes(const Column& column) {
  return element_size(column.type()) * size_t(column.components());
}

}  // namespace

StoreGather::StoreGather(MPI_Comm comm, std::vector<RowOwners> tables) {
  MPI_Comm_dup(comm, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  for (RowOwners& t : tables) {
    Listed l{std::move(t.table), std::move(t.owner), std::vector<std::vector<int32_t>>(size_t(size_))};
    for (size_t row = 0; row < l.owner.size(); ++row) {
      const int32_t o = l.owner[row];
      if (o < 0 || o >= size_)
        throw Error(fmt::format("store gather: row {} of {} is owned by rank {}, not one of the job's {}",
                                row, l.table, o, size_));
      l.rows[size_t(o)].push_back(int32_t(row));
    }
    tables_.push_back(std::move(l));
  }
}

StoreGather::~StoreGather() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

int64_t StoreGather::bytes_from(int32_t rank, const Store& store) const {
  int64_t bytes = 0;
  for (const Listed& l : tables_)
    for (const auto& column : store.table(l.table).columns())
      bytes += int64_t(l.rows[size_t(rank)].size() * row_bytes(*column));
  return bytes;
}

void StoreGather::to_root(Store& store) {
  // Every rank holds the same tables and rows, so every rank finds the same fault and throws it before
  // any message is posted.
  for (const Listed& l : tables_) {
    if (!store.has(l.table)) throw Error(fmt::format("store gather: the store has no table {}", l.table));
    if (store.table(l.table).size() != l.owner.size())
      throw Error(fmt::format("store gather: {} has {} rows, its owners {}", l.table,
                              store.table(l.table).size(), l.owner.size()));
  }
  std::vector<int> counts(static_cast<size_t>(size_)), displacements(static_cast<size_t>(size_));
  int64_t total = 0;
  for (int32_t r = 0; r < size_; ++r) {
    const int64_t bytes = r == 0 ? 0 : bytes_from(r, store);
    if (bytes > INT_MAX)
      throw Error(
          fmt::format("store gather: rank {} would send {} bytes at once, more than 2 GiB", r, bytes));
    counts[size_t(r)] = int(bytes);
    displacements[size_t(r)] = int(total);
    total += bytes;
  }
  if (total > INT_MAX) throw Error(fmt::format("store gather: {} bytes to rank 0, more than 2 GiB", total));

  const auto mine = size_t(counts[size_t(rank_)]);
  std::vector<std::byte> send(rank_ == 0 ? 0 : mine);
  size_t at = 0;
  if (rank_ != 0)
    for (const Listed& l : tables_)
      for (const auto& column : store.table(l.table).columns()) {
        const size_t width = row_bytes(*column);
        for (int32_t row : l.rows[size_t(rank_)])
          std::memcpy(send.data() + at, column->data() + size_t(row) * width, width), at += width;
      }
  if (rank_ == 0) buffer_.resize(size_t(total));
  MPI_Gatherv(send.data(), int(send.size()), MPI_BYTE, buffer_.data(), counts.data(), displacements.data(),
              MPI_BYTE, 0, comm_);
  if (rank_ != 0) return;
  at = 0;
  for (int32_t r = 1; r < size_; ++r)
    for (const Listed& l : tables_)
      for (const auto& column : store.table(l.table).columns()) {
        const size_t width = row_bytes(*column);
        for (int32_t row : l.rows[size_t(r)])
          std::memcpy(column->data() + size_t(row) * width, buffer_.data() + at, width), at += width;
      }
  bytes_received_ = total;
}

}  // namespace rift
