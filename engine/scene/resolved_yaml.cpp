#include "engine/scene/resolved_yaml.hpp"

#include "engine/core/fnv1a.hpp"

namespace rift {

std::string emit_resolved_yaml(const ResolvedNode& read) {
  return "# Resolved scene: every key, defaults filled, overrides applied (docs/scene-format.md).\n" +
         emit_resolved_tree(read);
}

std::string fnv1a64_hex(std::string_view text) {
  return hex16(fnv1a64(text.data(), text.size()));
}

std::string scene_hash(const Scene& scene) {
  std::string text = scene.resolved_yaml;
  if (scene.mesh.file) text += "# mesh.file content fnv1a64 " + scene.mesh.file_fnv1a64 + "\n";
  if (scene.fluid && scene.fluid->mesh && scene.fluid->mesh->file)
    text += "# fluid.mesh.file content fnv1a64 " + scene.fluid->mesh->file_fnv1a64 + "\n";
  return fnv1a64_hex(text);
}

}  // namespace rift
