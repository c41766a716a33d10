#pragma once
// A 64-bit FNV-1a digest of every column of every table: equal hashes mean bitwise-equal state.
// Used by determinism and restart tests and printed in the run summary.
#include <cstdint>
#include <cstdio>
#include <string>

#include "engine/core/table.hpp"

namespace rift {

inline uint64_t fnv1a(const void* data, size_t bytes, uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

inline uint64_t state_hash(const Store& store) {
  uint64_t h = 1469598103934665603ull;
  for (const auto& table : store.tables())
    for (const auto& column : table->columns()) {
      h = fnv1a(column->key().data(), column->key().size(), h);
      h = fnv1a(column->data(), column->bytes(), h);
    }
  return h;
}

inline std::string hex64(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace rift
