#pragma once
// Items grouped by key, each group in item order: a stable counting sort into offsets (compressed rows).
// It turns a scatter (item i adds to the sum of key[i]) into a gather (each key sums its own items in
// item order): the gather runs in parallel over keys, and since each key adds its items in the order the
// scatter did, the sums keep their bits on any thread count.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rift {

struct Groups {
  std::vector<int32_t> start;  // key_count + 1 offsets into items
  std::vector<int32_t> items;  // item indices grouped by key, ascending within each group

  // keys: 1 per item; a negative key puts the item in no group.
  void build(std::span<const int32_t> keys, size_t key_count) {
    start.assign(key_count + 1, 0);
    for (int32_t k : keys)
      if (k >= 0) ++start[size_t(k) + 1];
    for (size_t k = 0; k < key_count; ++k) start[k + 1] += start[k];
    items.resize(size_t(start[key_count]));
    next_.assign(start.begin(), start.end() - 1);
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] >= 0) items[size_t(next_[size_t(keys[i])]++)] = int32_t(i);
  }
  size_t size() const { return start.empty() ? 0 : start.size() - 1; }
  std::span<const int32_t> of(size_t key) const {
    return {items.data() + start[key], items.data() + start[key + 1]};
  }

 private:
  std::vector<int32_t> next_;
};

}  // namespace rift
