#pragma once
// Stable handles for entity kinds whose members come and go (contact pairs, broken joints, fluid
// cells after remeshing). A Handle names a slot and the generation it was issued in; the map turns it
// into the entity's current dense row, which changes when the table swap-removes. A handle whose
// slot was freed (generation bumped) resolves to nothing, so stale handles are detected, never
// silently aliased. Slots are reused in LIFO order; all storage is flat vectors (no per-entity heap).
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace rift {

struct Handle {
  uint32_t slot = std::numeric_limits<uint32_t>::max();
  uint32_t generation = 0;
  bool valid() const { return slot != std::numeric_limits<uint32_t>::max(); }
  friend bool operator==(Handle a, Handle b) { return a.slot == b.slot && a.generation == b.generation; }
};

class HandleMap {
 public:
  // Registers a new entity at dense row `row` (normally the table's previous size).
  Handle insert(uint32_t row) {
    uint32_t slot;
    if (!free_.empty()) {
      slot = free_.back();
      free_.pop_back();
    } else {
      slot = static_cast<uint32_t>(row_of_slot_.size());
      row_of_slot_.push_back(0);
      generation_.push_back(0);
    }
    row_of_slot_[slot] = row;
    if (slot_of_row_.size() <= row) slot_of_row_.resize(row + 1);
    slot_of_row_[row] = slot;
    return {slot, generation_[slot]};
  }

  std::optional<uint32_t> row(Handle h) const {
    if (!h.valid() || h.slot >= generation_.size() || generation_[h.slot] != h.generation)
      return std::nullopt;
    return row_of_slot_[h.slot];
  }

  Handle handle_at(uint32_t row) const { return {slot_of_row_[row], generation_[slot_of_row_[row]]}; }

  // Mirrors Table::swap_remove(row): the entity at `row` dies, the one at `last` moves into `row`.
  void swap_remove(uint32_t row, uint32_t last) {
    const uint32_t dead = slot_of_row_[row];
    ++generation_[dead];
    free_.push_back(dead);
    if (row != last) {
      const uint32_t moved = slot_of_row_[last];
      slot_of_row_[row] = moved;
      row_of_slot_[moved] = row;
    }
    slot_of_row_.resize(last);
  }

  size_t size() const { return slot_of_row_.size(); }

 private:
  std::vector<uint32_t> row_of_slot_, generation_, slot_of_row_, free_;
};

}  // namespace rift
