#pragma once
// Checks that a system changes only what it declared (engine/schedule/system.hpp, Access): every column
// whose contents change while it runs must be among its writes, and a table whose row count changes among
// its resizes (or the system declares changes_topology). The step graph derives its order from those
// declarations, so a write that is not declared is a data race waiting for the thread count that exposes it.
//
// How: a fingerprint of the store (rows per table, a hash of every column's bytes) before and after the
// system runs finds writes by their effect, wherever the system got its spans (at set-up or in run); it
// does not see a write that leaves the same bytes. Reads: every column the system looks up while it runs
// (ColumnLookupObserver, engine/core/table.hpp) must be among its reads or writes; a span it took at
// set-up and reads later is not seen.
#include <cstdint>
#include <mutex>
#include <set>
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

// Collects the keys of the columns looked up while installed (one at a time, process-wide).
class LookupRecorder : public ColumnLookupObserver {
 public:
  LookupRecorder();
  ~LookupRecorder() override;
  void looked_up(const Column& column) override;
  std::vector<std::string> keys() const;  // sorted, once each

 private:
  mutable std::mutex mutex_;
  std::set<std::string> keys_;
};

// The columns `system` looked up that its access does not name (reads or writes): "" when none.
std::string undeclared_lookups(const std::vector<std::string>& looked_up, const Access& access,
                               const std::string& system);

}  // namespace rift
