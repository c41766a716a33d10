#pragma once
// A 64-bit FNV-1a digest of every column of every table: equal hashes mean bitwise-equal state.
// Used by determinism and restart tests and printed in the run summary.
#include <cstdint>
#include <cstdio>
#include <string>

#include "engine/core/fnv1a.hpp"
#include "engine/core/table.hpp"

namespace rift {

// FNV-1a over the columns, from a basis of its own (not fnv1a64_basis): the state hashes that the docs
// and earlier runs quote were made with it.
inline uint64_t state_hash(const Store& store) {
  uint64_t h = 1469598103934665603ull;
  for (const auto& table : store.tables())
    for (const auto& column : table->columns()) {
      h = fnv1a64(column->key().data(), column->key().size(), h);
      h = fnv1a64(column->data(), column->bytes(), h);
    }
  return h;
}

inline std::string hex64(uint64_t h) {
  return hex16(h);
}

}  // namespace rift
