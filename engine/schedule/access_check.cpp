#include "engine/schedule/access_check.hpp"

#include <algorithm>
#include <cstring>
#include <map>

#include "engine/core/fnv1a.hpp"

namespace rift {

namespace {

// FNV-1a over 8-byte words (then the tail bytes): a change detector, 8 x faster than byte-wise.
uint64_t bytes_hash(const std::byte* data, size_t size) {
  uint64_t h = fnv1a64_basis;
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t word;
    std::memcpy(&word, data + i, 8);
    h = (h ^ word) * 1099511628211ull;
  }
  return fnv1a64(data + i, size - i, h);
}

}  // namespace

StoreFingerprint fingerprint(const Store& store) {
  StoreFingerprint f;
  for (const auto& table : store.tables()) {
    f.entries.push_back({table->name(), static_cast<uint64_t>(table->size())});
    for (const auto& column : table->columns())
      f.entries.push_back({column->key(), bytes_hash(column->data(), column->bytes())});
  }
  return f;
}

std::string undeclared_changes(const Store& store, const StoreFingerprint& before, const Access& access,
                               const std::string& system) {
  std::map<std::string, uint64_t> was;
  for (const auto& e : before.entries) was[e.key] = e.value;
  const auto declared = [&](const std::string& key) {
    return std::find(access.writes.begin(), access.writes.end(), key) != access.writes.end();
  };
  const std::vector<StoreFingerprint::Entry> now = fingerprint(store).entries;
  std::vector<std::string> resized;  // tables whose row count changed: all their columns change with it
  for (const auto& e : now)
    if (e.key.find('.') == std::string::npos && was.count(e.key) && was[e.key] != e.value)
      resized.push_back(e.key);
  std::string report;
  for (const auto& e : now) {
    const auto it = was.find(e.key);
    const bool is_table = e.key.find('.') == std::string::npos;
    if (it == was.end()) {
      if (!access.changes_topology)
        report += "  " + system + " added " + (is_table ? "table " : "column ") + e.key +
                  " while it ran: declare changes_topology in its access()\n";
      continue;
    }
    if (it->second == e.value) continue;
    const std::string table = e.key.substr(0, e.key.find('.'));
    const bool may_resize = access.changes_topology || std::find(access.resizes.begin(), access.resizes.end(),
                                                                 table) != access.resizes.end();
    if (is_table) {
      if (!may_resize)
        report += "  " + system + " changed the row count of " + e.key + " (" + std::to_string(it->second) +
                  " to " + std::to_string(e.value) + ") without declaring it among its resizes\n";
      continue;
    }
    const bool resized_with_table =
        may_resize && std::find(resized.begin(), resized.end(), table) != resized.end();
    if (!declared(e.key) && !resized_with_table)
      report += "  " + system + " wrote " + e.key + " without declaring it among its writes\n";
  }
  return report;
}

LookupRecorder::LookupRecorder() {
  set_column_lookup_observer(this);
}
LookupRecorder::~LookupRecorder() {
  set_column_lookup_observer(nullptr);
}

void LookupRecorder::looked_up(const Column& column) {
  std::lock_guard lock(mutex_);
  keys_.insert(column.key());
}

std::vector<std::string> LookupRecorder::keys() const {
  std::lock_guard lock(mutex_);
  return {keys_.begin(), keys_.end()};
}

std::string undeclared_lookups(const std::vector<std::string>& looked_up, const Access& access,
                               const std::string& system) {
  const auto named = [&](const std::string& key) {
    for (const auto* list : {&access.reads, &access.writes})
      if (std::find(list->begin(), list->end(), key) != list->end()) return true;
    return false;
  };
  std::string report;
  for (const auto& key : looked_up)
    if (!named(key) && !access.changes_topology)
      report += "  " + system + " looked up " + key + " without declaring it among its reads\n";
  return report;
}

}  // namespace rift
