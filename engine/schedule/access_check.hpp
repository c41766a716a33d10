#pragma once
// Checks that a system changes only what it declared (engine/schedule/system.hpp, Access): every column
// whose contents change while it runs must be among its writes, and a table whose row count changes among
// its resizes (or the system declares changes_topology). The step graph derives its order from those
// declarations, so a write that is not declared is a data race waiting for the thread count that exposes it.
//
// How: a fingerprint of the store (rows per table, a hash of every column's bytes) before and after the
// system runs. It finds writes by their effect, wherever the system got its spans (at set-up or in run),
// and it does not see reads (a read leaves no trace) or a write that leaves the same bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/schedule/system.hpp"

namespace rift {

struct StoreFingerprint {
  struct Entry {
    std::string key;  // "table" (its rows) or "table.column" (its bytes)
    uint64_t value = 0;
  };
  std::vector<Entry> entries;  // in the store's order
};

StoreFingerprint fingerprint(const Store& store);

// What `system` changed between `before` and now without declaring it: "" when nothing; else one line per
// column or table, with what to declare.
std::string undeclared_changes(const Store& store, const StoreFingerprint& before, const Access& access,
                               const std::string& system);

}  // namespace rift
