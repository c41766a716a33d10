#pragma once
// The elements a system computes as runs of consecutive ids, cut at the multiples of a grain and grouped
// into blocks, one per grain-aligned stretch: with every id, the blocks are parallel_for's, so per-block
// results keep their order and their bits; with some ids left out (handed to another pass, or to another
// process), each block still holds only ids of its stretch.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/schedule/parallel.hpp"

namespace rift {

class RunBlocks {
 public:
  using Run = std::pair<size_t, size_t>;  // [begin, end)

  explicit RunBlocks(size_t grain) : grain_(grain) {}

  // The ranges (ascending, disjoint), each cut at the multiples of the grain.
  void set(std::span<const Run> ranges) {
    runs_.clear();
    for (auto [begin, end] : ranges)
      while (begin < end) {
        const size_t stop = std::min(end, (begin / grain_ + 1) * grain_);
        runs_.emplace_back(begin, stop);
        begin = stop;
      }
    group();
  }
  void set_all(size_t count) {
    const Run all{0, count};
    set({&all, 1});
  }
  // Keeps only the ids of `ids` (ascending) among the runs.
  void keep_only(std::span<const int32_t> ids) {
    std::vector<Run> kept;
    auto next = ids.begin();
    for (const auto& [begin, end] : runs_) {
      next = std::lower_bound(next, ids.end(), static_cast<int32_t>(begin));
      for (; next != ids.end() && static_cast<size_t>(*next) < end; ++next) {
        const auto e = static_cast<size_t>(*next);
        if (!kept.empty() && kept.back().second == e)
          kept.back().second = e + 1;
        else
          kept.emplace_back(e, e + 1);
      }
    }
    runs_ = std::move(kept);
    group();
  }

  size_t blocks() const { return block_first_run_.size() - 1; }
  // body(block, begin, end) for each run, the blocks in parallel.
  template <class Body>
  void parallel_runs(const Body& body) const {
    parallel_for(blocks(), 1, [&](size_t b, size_t) {
      for (size_t r = block_first_run_[b]; r < block_first_run_[b + 1]; ++r)
        body(b, runs_[r].first, runs_[r].second);
    });
  }

 private:
  void group() {
    block_first_run_.clear();
    for (size_t r = 0; r < runs_.size(); ++r)
      if (r == 0 || runs_[r].first / grain_ != runs_[r - 1].first / grain_) block_first_run_.push_back(r);
    block_first_run_.push_back(runs_.size());
  }

  size_t grain_;
  std::vector<Run> runs_;
  std::vector<size_t> block_first_run_{0};
};

}  // namespace rift
