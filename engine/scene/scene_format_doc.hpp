#pragma once
// docs/scene-format.md as the binary carries it, and the two things code reads from it: the key tables
// (every documented key path with its type, unit, default, range and meaning) and the complete examples
// (YAML scenes that together read every documented key). The docs test and `rift schema` share these.
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace rift {

// The text of docs/scene-format.md when the binary was configured.
std::string_view scene_format_doc();

// One row of a key table, cells as written (markdown), escaped pipes ("\|") restored.
struct DocumentedKey {
  std::string key;  // the path without list indices: "solid.materials.density", "ramp.rate", "scene"
  std::string type, unit, default_value, range;
  std::string meaning;  // the "meaning" column (the sections table: "holds")
};

// Every table row whose first cell is a `key`, by key path.
std::map<std::string, DocumentedKey> documented_keys(std::string_view doc);

// The ```yaml block under each "## Complete example..." heading, in order; empty when a heading has no
// complete block. No one scene can use every key (a fluid-only scene's fluid.mesh excludes mesh,
// fracture_flow excludes solid.fracture.crack_pressure), so there are several.
std::vector<std::string> complete_examples(std::string_view doc);

}  // namespace rift
