#include "engine/distributed/log_gather.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <numeric>
#include <vector>

#include "engine/core/error.hpp"

namespace rift {
namespace {

size_t row_bytes(const Table& log) {
  size_t bytes = 0;
  for (const auto& c : log.columns()) bytes += element_size(c->type()) * size_t(c->components());
  return bytes;
}

// Row r's values, column after column.
void pack_row(const Table& log, size_t r, std::byte* out) {
  for (const auto& c : log.columns()) {
    const size_t w = element_size(c->type()) * size_t(c->components());
    std::memcpy(out, c->data() + r * w, w);
    out += w;
  }
}

void unpack_row(Table& log, size_t r, const std::byte* in) {
  for (const auto& c : log.columns()) {
    const size_t w = element_size(c->type()) * size_t(c->components());
    std::memcpy(c->data() + r * w, in, w);
    in += w;
  }
}

}  // namespace

void gather_log_to_root(MPI_Comm comm, Table& log, size_t prefix, const std::function<bool(size_t)>& keep,
                        const std::function<bool(const Table&, size_t, size_t)>& before) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (log.size() < prefix)
    throw Error(fmt::format("log gather: {} has {} rows, fewer than the {} written at set-up", log.name(),
                            log.size(), prefix));
  const size_t width = row_bytes(log);
  std::vector<std::byte> mine;
  for (size_t r = prefix; r < log.size(); ++r)
    if (keep(r)) {
      mine.resize(mine.size() + width);
      pack_row(log, r, mine.data() + mine.size() - width);
    }
  if (mine.size() > size_t(INT_MAX))
    throw Error(fmt::format("log gather: rank {} would send {} bytes of {}, more than 2 GiB", rank,
                            mine.size(), log.name()));
  int count = int(mine.size());
  std::vector<int> counts(static_cast<size_t>(size)), displacements(static_cast<size_t>(size));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  int64_t total = 0;
  for (int r = 0; r < size; ++r) {
    displacements[size_t(r)] = int(std::min<int64_t>(total, INT_MAX));
    total += counts[size_t(r)];
  }
  // Only rank 0 knows the total; it tells the others whether the gather may go ahead, so that all of
  // them stop together.
  int too_large = rank == 0 && total > INT_MAX;
  MPI_Bcast(&too_large, 1, MPI_INT, 0, comm);
  if (too_large)
    throw Error(fmt::format("log gather: {} rows of {} to rank 0 exceed 2 GiB", total, log.name()));
  std::vector<std::byte> all(rank == 0 ? size_t(total) : 0);
  MPI_Gatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), displacements.data(), MPI_BYTE, 0,
              comm);
  if (rank != 0) return;

  const size_t rows = size_t(total) / width;
  log.resize(prefix + rows);
  for (size_t i = 0; i < rows; ++i) unpack_row(log, prefix + i, all.data() + i * width);
  std::vector<size_t> order(rows);
  std::iota(order.begin(), order.end(), prefix);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return before(log, a, b); });
  std::vector<std::byte> sorted(rows * width);
  for (size_t i = 0; i < rows; ++i) pack_row(log, order[i], sorted.data() + i * width);
  for (size_t i = 0; i < rows; ++i) unpack_row(log, prefix + i, sorted.data() + i * width);
}

}  // namespace rift
