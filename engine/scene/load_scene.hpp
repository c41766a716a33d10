#pragma once
// Reading a scene file into a checked, completed Scene. The format is in docs/scene-format.md.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"
#include "engine/scene/scene_diagnostic.hpp"

namespace rift {

struct SceneLoadResult {
  std::optional<Scene> scene;           // set only when `errors` is empty
  std::vector<SceneDiagnostic> errors;  // every problem of the file and the overrides, in reading order
  // Key paths the reader asked for, without list indices ("solid.materials.density"); time-function
  // keys start afresh ("ramp.rate"). Lets a test check that docs/scene-format.md names every key.
  std::vector<std::string> consumed_keys;
};

// A scene is hand-written YAML of a few kilobytes; a larger file (or a device such as /dev/zero, a FIFO)
// is refused before it is parsed, so that no input can make the reader exhaust memory.
inline constexpr uint64_t scene_file_max_bytes = 4u << 20;

// Reads `path` (a regular file of at most scene_file_max_bytes), applies `overrides` ("key.path=value", list
// items as materials[0].density), checks every key and fills defaults. Collects all errors instead of
// stopping at the first.
SceneLoadResult read_scene_file(const std::string& path, const std::vector<std::string>& overrides = {});

class SchemaRecorder;

// The same for YAML text: `file_label` names it in diagnostics and becomes Scene::source_file;
// relative mesh paths start at `base_dir`. With a `recorder`, every key's rule is reported to it as it
// is read (schema_recorder.hpp).
SceneLoadResult read_scene_text(const std::string& yaml, const std::string& file_label,
                                const std::string& base_dir, const std::vector<std::string>& overrides = {},
                                SchemaRecorder* recorder = nullptr);

// read_scene_file, throwing rift::Error with every diagnostic, one per line, when there is any.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace rift
