#pragma once
// Which keys two resolved scenes (their YAML, as scene.yaml holds it) differ in: the paths of every scalar,
// list or section present in one and not the other or with another value. A restart uses it to tell an
// extension (only the end time or the output settings changed) from another scene, and to name the keys.
#include <string>
#include <vector>

namespace rift {

// Paths such as "time.end" or "solid.materials[0].density", sorted; empty when the scenes are the same.
// A document that does not parse differs at "" (the whole scene).
std::vector<std::string> differing_keys(const std::string& yaml_a, const std::string& yaml_b);

// True when every path is time.end or under output: what a restart may change to extend a run.
bool only_extension_keys(const std::vector<std::string>& paths);

}  // namespace rift
