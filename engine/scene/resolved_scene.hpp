#pragma once
// The scene as the reader understood it, recorded while it reads: every key each MapReader accessor read,
// with the value it returned (the file's, an override's or the default), in the order first read. The
// resolved YAML (resolved_yaml.hpp) is this tree printed, so the reader is the one table of keys that both
// reads a scene and writes it back: a key the reader knows is written, with the rule it was read by, and
// nothing else is. Keys of variants a scene does not use (MapReader::unused) are not recorded.
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/scene/time_function.hpp"

namespace rift {

struct ResolvedNode {
  enum class Kind { scalar, mapping, list };
  Kind kind = Kind::mapping;
  std::string text;  // scalar: the value as YAML flow text ("1.0e-03", "\"name\"", "[x, y]", "{ramp: ...}")
  std::vector<std::pair<std::string, std::unique_ptr<ResolvedNode>>> entries;  // mapping, in reading order
  std::vector<std::unique_ptr<ResolvedNode>> items;                            // list: one mapping per item

  // The entry `key` of a mapping, added at the end the first time; a second reading of the key (another
  // pass over the same mapping) replaces its value in place.
  ResolvedNode& entry(std::string_view key, Kind kind);
  // Item `index` of a list, added (with the items before it) the first time.
  ResolvedNode& item(size_t index);
};

// The tree as block YAML, two spaces per level; strings double-quoted, numbers that read back bit-identical.
std::string emit_resolved_tree(const ResolvedNode& root);

// Scalar texts for ResolvedNode::text, as the accessors record them.
std::string resolved_string(std::string_view s);  // always double-quoted: no name reads as a number
std::string resolved_vec3(const double v[3]);
// A number, {ramp: {value, start_time, rate, limit}} or {table: [[t, v], ...]}.
std::string resolved_time_function(const TimeFunction& f);

}  // namespace rift
