#include "kernels/contact_broad_phase.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rift::kernels {

namespace {

constexpr int kDigitBits = 11;
constexpr size_t kBuckets = size_t{1} << kDigitBits;
constexpr int kMaxDigits = (64 + kDigitBits - 1) / kDigitBits;  // 6
constexpr double kMaxCellsPerAxis = 1048576.0;                  // 2^20

template <class T>
void ensure_size(std::vector<T>& v, size_t n) {
  if (n > v.size()) v.resize(n);
}

uint64_t key_of(const BroadPhaseWorkspace::Entry& e) {
  return e.key;
}

// Stable LSD radix sort of v[0, n) by key_of, using tmp[0, n) as scratch and count (kMaxDigits x kBuckets)
// for the histograms; only the digits below the highest set bit are looked at, and digits that are equal
// for every key are skipped. The result ends up in v.
template <class T>
void radix_sort(std::vector<T>& v, std::vector<T>& tmp, std::vector<size_t>& count, size_t n) {
  if (n < 2) return;
  uint64_t bits = 0;
  for (size_t i = 0; i < n; ++i) bits |= key_of(v[i]);
  int digits = 0;
  while (digits < kMaxDigits && (bits >> (digits * kDigitBits)) != 0) ++digits;
  ensure_size(count, kMaxDigits * kBuckets);
  std::fill_n(count.begin(), static_cast<size_t>(digits) * kBuckets, size_t{0});
  for (size_t i = 0; i < n; ++i) {
    const uint64_t k = key_of(v[i]);
    for (int d = 0; d < digits; ++d) ++count[d * kBuckets + ((k >> (d * kDigitBits)) & (kBuckets - 1))];
  }
  T* src = v.data();
  T* dst = tmp.data();
  for (int d = 0; d < digits; ++d) {
    size_t* c = &count[d * kBuckets];
    const uint64_t first = (key_of(src[0]) >> (d * kDigitBits)) & (kBuckets - 1);
    if (c[first] == n) continue;  // every key has this digit
    size_t sum = 0;
    for (size_t b = 0; b < kBuckets; ++b) {
      const size_t here = c[b];
      c[b] = sum;
      sum += here;
    }
    for (size_t i = 0; i < n; ++i) dst[c[(key_of(src[i]) >> (d * kDigitBits)) & (kBuckets - 1)]++] = src[i];
    std::swap(src, dst);
  }
  if (src != v.data()) std::copy(src, src + n, v.data());
}

inline bool overlap(const double* p, const double* q) {
  return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] && q[2] <= p[5];
}

// Pair keys rank_a << 32 | rank_b (rank_a < rank_b): counting sort by rank_a (one histogram, one scatter;
// ranks < n), then each rank_a's run sorted by rank_b (runs are short: the partners of one box). The sorted
// keys end up in ws.keys_tmp.
void sort_pair_keys(BroadPhaseWorkspace& ws, size_t count, size_t ranks) {
  ensure_size(ws.keys_tmp, count);
  ensure_size(ws.count, ranks + 1);
  std::fill_n(ws.count.begin(), ranks + 1, size_t{0});
  for (size_t i = 0; i < count; ++i) ++ws.count[(ws.keys[i] >> 32) + 1];
  for (size_t r = 0; r < ranks; ++r) ws.count[r + 1] += ws.count[r];
  for (size_t i = 0; i < count; ++i) ws.keys_tmp[ws.count[ws.keys[i] >> 32]++] = ws.keys[i];
  size_t begin = 0;  // after the scatter, count[r] is the end of run r
  for (size_t r = 0; r < ranks; ++r) {
    const size_t end = ws.count[r];
    uint64_t* k = ws.keys_tmp.data();
    if (end - begin <= 32) {
      for (size_t i = begin + 1; i < end; ++i) {  // insertion sort
        const uint64_t v = k[i];
        size_t j = i;
        for (; j > begin && k[j - 1] > v; --j) k[j] = k[j - 1];
        k[j] = v;
      }
    } else {
      std::sort(k + begin, k + end);
    }
    begin = end;
  }
}

// Decode the sorted keys (ws.keys_tmp), drop duplicates and excluded pairs, into ws.pairs; returns the
// count of excluded pairs removed.
size_t finish_pairs(BroadPhaseWorkspace& ws, size_t count, std::span<const ContactPair> excluded,
                    size_t& out) {
  ensure_size(ws.pairs, count);
  size_t removed = 0, e = 0;
  out = 0;
  for (size_t i = 0; i < count; ++i) {
    const uint64_t key = ws.keys_tmp[i];
    if (i > 0 && key == ws.keys_tmp[i - 1]) continue;
    const ContactPair p{ws.rank_id[key >> 32], ws.rank_id[key & 0xffffffffu]};
    while (e < excluded.size() && excluded[e] < p) ++e;
    if (e < excluded.size() && excluded[e] == p) {
      ++removed;
      continue;
    }
    ws.pairs[out++] = p;
  }
  return removed;
}

constexpr size_t kChunkBoxes = 4096;

size_t chunk_key_capacity(const BroadPhaseWorkspace& ws) {
  size_t c = 0;
  for (const auto& k : ws.chunk_keys) c += k.capacity();
  return c;
}

struct SweepContext {
  BroadPhaseWorkspace* ws;
  size_t n;
  uint64_t nx, nxy;  // cells per row and per layer (padding included)
};

// One chunk of the sweep: the cells whose entries lie in [chunk_begin[k], chunk_begin[k + 1]), each tested
// against itself and its 13 later neighbours (5 runs of keys, header), which may lie in later chunks. The
// cursors start at the chunk's first cell (a binary search) and then only move forward.
void sweep_chunk(void* context, size_t k) {
  const SweepContext& c = *static_cast<SweepContext*>(context);
  BroadPhaseWorkspace& ws = *c.ws;
  const auto& entries = ws.entries;
  std::vector<uint64_t>& keys = ws.chunk_keys[k];
  keys.resize(0);
  size_t tested = 0;
  auto emit = [&](size_t s, size_t t) {
    ++tested;
    if (!overlap(&ws.sorted_box[6 * s], &ws.sorted_box[6 * t])) return;
    const uint64_t a = ws.sorted_rank[s], b = ws.sorted_rank[t];
    if (a == b) return;
    keys.push_back(a < b ? (a << 32) | b : (b << 32) | a);
  };
  const uint64_t row_lo[5] = {1, c.nx - 1, c.nxy - c.nx - 1, c.nxy - 1, c.nxy + c.nx - 1};
  const uint64_t row_hi[5] = {1, c.nx + 1, c.nxy - c.nx + 1, c.nxy + 1, c.nxy + c.nx + 1};
  const size_t first = ws.chunk_begin[k], last = ws.chunk_begin[k + 1];
  size_t cursor[5];
  for (int r = 0; r < 5; ++r) {
    const uint64_t lo = entries[first].key + row_lo[r];
    cursor[r] = static_cast<size_t>(
        std::lower_bound(entries.begin() + static_cast<std::ptrdiff_t>(first),
                         entries.begin() + static_cast<std::ptrdiff_t>(c.n), lo,
                         [](const BroadPhaseWorkspace::Entry& e, uint64_t v) { return e.key < v; }) -
        entries.begin());
  }
  for (size_t s = first; s < last;) {
    const uint64_t key = entries[s].key;
    size_t e = s + 1;
    while (e < c.n && entries[e].key == key) ++e;
    for (size_t i = s; i < e; ++i)
      for (size_t j = i + 1; j < e; ++j) emit(i, j);
    for (int r = 0; r < 5; ++r) {
      const uint64_t lo = key + row_lo[r], hi = key + row_hi[r];
      size_t& q0 = cursor[r];
      if (q0 < e) q0 = e;
      while (q0 < c.n && entries[q0].key < lo) ++q0;
      for (size_t q = q0; q < c.n && entries[q].key <= hi; ++q)
        for (size_t i = s; i < e; ++i) emit(i, q);
    }
    s = e;
  }
  ws.chunk_tested[k] = tested;
}

}  // namespace

BroadPhaseStats contact_broad_phase(const BroadPhaseArgs& args, BroadPhaseWorkspace& ws) {
  auto capacity = [&ws] {
    return ws.entries.capacity() + ws.entries_tmp.capacity() + ws.id_entries.capacity() +
           ws.sorted_box.capacity() + ws.sorted_rank.capacity() + ws.rank_of_box.capacity() +
           ws.rank_id.capacity() + ws.keys.capacity() + ws.keys_tmp.capacity() + ws.count.capacity() +
           ws.pairs.capacity() + ws.chunk_keys.capacity() + ws.chunk_begin.capacity() +
           ws.chunk_tested.capacity() + chunk_key_capacity(ws);
  };
  const size_t cap_before = capacity();
  BroadPhaseStats st;
  const size_t n = args.ids.size();
  const double h = 0.5 * args.buffer;
  ws.pairs.resize(0);
  if (n == 0) return st;

  // Extent of the inflated cloud and the largest inflated edge.
  double gmin[3], gmax[3], edge = 0.0;
  for (int k = 0; k < 3; ++k) {
    gmin[k] = args.lo[k] - h;
    gmax[k] = args.hi[k] + h;
  }
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double l = args.lo[3 * i + k] - h, u = args.hi[3 * i + k] + h;
      gmin[k] = std::min(gmin[k], l);
      gmax[k] = std::max(gmax[k], u);
      edge = std::max(edge, u - l);
    }
  }
  double c = edge * (1.0 + 1e-6);
  for (int k = 0; k < 3; ++k) c = std::max(c, (gmax[k] - gmin[k]) / kMaxCellsPerAxis);
  if (!(c > 0.0)) c = 1.0;  // every box is the same point
  st.cell_size = c;
  const double inv_c = 1.0 / c;
  uint64_t dim[3];
  for (int k = 0; k < 3; ++k) dim[k] = static_cast<uint64_t>(std::floor((gmax[k] - gmin[k]) * inv_c)) + 3;

  // Cell keys, sorted.
  ensure_size(ws.entries, n);
  ensure_size(ws.entries_tmp, n);
  for (size_t i = 0; i < n; ++i) {
    uint64_t cell[3];
    for (int k = 0; k < 3; ++k) {
      const double t = std::floor((args.lo[3 * i + k] - h - gmin[k]) * inv_c);
      cell[k] = std::min(static_cast<uint64_t>(std::max(t, 0.0)), dim[k] - 3) + 1;
    }
    ws.entries[i] = {(cell[2] * dim[1] + cell[1]) * dim[0] + cell[0], static_cast<int32_t>(i)};
  }
  radix_sort(ws.entries, ws.entries_tmp, ws.count, n);

  // Ranks: ids in increasing order get ranks 0, 1, ... (equal ids share one), so that pairs sorted by rank
  // are sorted by id, and the pair sort needs only n buckets whatever the ids.
  ensure_size(ws.id_entries, n);
  for (size_t i = 0; i < n; ++i)
    ws.id_entries[i] = {static_cast<uint64_t>(args.ids[i]), static_cast<int32_t>(i)};
  radix_sort(ws.id_entries, ws.entries_tmp, ws.count, n);
  ensure_size(ws.rank_of_box, n);
  ensure_size(ws.rank_id, n);
  uint32_t rank = 0;
  for (size_t s = 0; s < n; ++s) {
    if (s > 0 && ws.id_entries[s].key != ws.id_entries[s - 1].key) ++rank;
    ws.rank_of_box[static_cast<size_t>(ws.id_entries[s].box)] = rank;
    ws.rank_id[rank] = static_cast<int32_t>(ws.id_entries[s].key);
  }
  const size_t ranks = static_cast<size_t>(rank) + 1;

  // Boxes in cell order.
  ensure_size(ws.sorted_box, 6 * n);
  ensure_size(ws.sorted_rank, n);
  for (size_t s = 0; s < n; ++s) {
    const size_t i = static_cast<size_t>(ws.entries[s].box);
    double* b = &ws.sorted_box[6 * s];
    for (int k = 0; k < 3; ++k) {
      b[k] = args.lo[3 * i + k] - h;
      b[3 + k] = args.hi[3 * i + k] + h;
    }
    ws.sorted_rank[s] = ws.rank_of_box[i];
  }

  // Sweep, in chunks of about kChunkBoxes entries that start on a cell boundary.
  ws.chunk_begin.resize(0);
  for (size_t s = 0; s < n;) {
    ws.chunk_begin.push_back(s);
    s = std::min(n, s + kChunkBoxes);
    while (s < n && ws.entries[s].key == ws.entries[s - 1].key) ++s;
  }
  ws.chunk_begin.push_back(n);
  const size_t chunks = ws.chunk_begin.size() - 1;
  if (ws.chunk_keys.size() < chunks) ws.chunk_keys.resize(chunks);
  ensure_size(ws.chunk_tested, chunks);
  SweepContext sweep{&ws, n, dim[0], dim[0] * dim[1]};
  if (args.run_chunks)
    args.run_chunks(chunks, &sweep_chunk, &sweep);
  else
    for (size_t k = 0; k < chunks; ++k) sweep_chunk(&sweep, k);
  size_t found = 0;
  for (size_t k = 0; k < chunks; ++k) {
    found += ws.chunk_keys[k].size();
    st.tested += ws.chunk_tested[k];
  }
  ws.keys.resize(found);
  found = 0;
  for (size_t k = 0; k < chunks; ++k) {
    std::copy(ws.chunk_keys[k].begin(), ws.chunk_keys[k].end(),
              ws.keys.begin() + static_cast<std::ptrdiff_t>(found));
    found += ws.chunk_keys[k].size();
  }
  for (size_t s = 0; s < n; ++s)
    if (s == 0 || ws.entries[s].key != ws.entries[s - 1].key) ++st.cells;

  size_t out = 0;
  sort_pair_keys(ws, ws.keys.size(), ranks);
  st.excluded = finish_pairs(ws, ws.keys.size(), args.excluded, out);
  ws.pairs.resize(out);
  st.pairs = out;
  if (capacity() != cap_before) ++ws.grows;
  return st;
}

std::vector<ContactPair> contact_broad_phase_brute_force(const BroadPhaseArgs& args) {
  const size_t n = args.ids.size();
  const double h = 0.5 * args.buffer;
  std::vector<double> box(6 * n);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      box[6 * i + k] = args.lo[3 * i + k] - h;
      box[6 * i + 3 + k] = args.hi[3 * i + k] + h;
    }
  std::vector<ContactPair> pairs;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if (overlap(&box[6 * i], &box[6 * j]) && args.ids[i] != args.ids[j])
        pairs.push_back({std::min(args.ids[i], args.ids[j]), std::max(args.ids[i], args.ids[j])});
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<ContactPair> kept;
  kept.reserve(pairs.size());
  std::set_difference(pairs.begin(), pairs.end(), args.excluded.begin(), args.excluded.end(),
                      std::back_inserter(kept));
  return kept;
}

void tet_bounding_boxes(std::span<const double> x, std::span<const int32_t> tet_nodes,
                        std::span<const int32_t> ids, std::span<double> lo, std::span<double> hi,
                        size_t begin, size_t end) {
  for (size_t k = begin; k < end; ++k) {
    const size_t t = static_cast<size_t>(ids[k]);
    for (int d = 0; d < 3; ++d) {
      double l = x[3 * static_cast<size_t>(tet_nodes[4 * t]) + d], u = l;
      for (int c = 1; c < 4; ++c) {
        const double v = x[3 * static_cast<size_t>(tet_nodes[4 * t + c]) + d];
        l = std::min(l, v);
        u = std::max(u, v);
      }
      lo[3 * k + d] = l;
      hi[3 * k + d] = u;
    }
  }
}

double max_node_displacement(std::span<const double> x, std::span<const double> x_ref, size_t begin,
                             size_t end) {
  double m2 = 0.0;
  for (size_t i = begin; i < end; ++i) {
    const double dx = x[3 * i] - x_ref[3 * i], dy = x[3 * i + 1] - x_ref[3 * i + 1],
                 dz = x[3 * i + 2] - x_ref[3 * i + 2];
    m2 = std::max(m2, dx * dx + dy * dy + dz * dz);
  }
  return std::sqrt(m2);
}

}  // namespace rift::kernels
