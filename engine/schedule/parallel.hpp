#pragma once
// Data parallelism inside a system. Ranges are cut into fixed-size blocks independent of the thread
// count, so any per-block partial result (sums, minima) combines in the same order on 1, 2 or 8
// threads: that is what makes reductions bitwise deterministic.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace rift {

// Calls body(begin, end) on consecutive blocks of `grain` items covering [0, count).
template <class Body>
void parallel_for(size_t count, size_t grain, const Body& body) {
  if (count == 0) return;
  const size_t blocks = (count + grain - 1) / grain;
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, blocks, 1),
      [&](const tbb::blocked_range<size_t>& r) {
        for (size_t b = r.begin(); b != r.end(); ++b) body(b * grain, std::min(count, (b + 1) * grain));
      },
      tbb::simple_partitioner());
}

// Deterministic sum: each fixed block produces a partial (body(begin, end) -> T), partials are added
// left to right. `partials` is caller-owned scratch so the hot path allocates nothing.
template <class T, class Body>
T parallel_sum(size_t count, size_t grain, std::vector<T>& partials, const Body& body) {
  const size_t blocks = count == 0 ? 0 : (count + grain - 1) / grain;
  if (partials.size() < blocks) partials.resize(blocks);
  parallel_for(count, grain, [&](size_t begin, size_t end) { partials[begin / grain] = body(begin, end); });
  T total{};
  for (size_t b = 0; b < blocks; ++b) total += partials[b];
  return total;
}

}  // namespace rift
