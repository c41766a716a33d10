#pragma once
// Command-line overrides of scene keys: "key.path=value", list items by index
// ("solid.materials[0].density=3000"). The value is read as YAML ("[0, 0, -9.81]", "{ramp: {...}}").
// Missing mappings on the way are created, so an override can add a key the file left at its default;
// a key the format does not know is then reported like a file key, located at "--set ...".
#include <string>
#include <vector>

#include "engine/scene/yaml_reader.hpp"
#include "engine/scene/yaml_tree.hpp"

namespace rift {

// Applies the overrides in order (a later one wins). Malformed ones are reported to `ctx` and skipped.
void apply_overrides(YamlNode& root, const std::vector<std::string>& overrides, ReadContext& ctx);

}  // namespace rift
