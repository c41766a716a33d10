#pragma once
// The JSON Schema (draft-07) of the scene format, for editors (VS Code's YAML extension, any
// yaml-language-server client) and validators: `rift schema`. It is made from the reader itself: the
// complete examples of docs/scene-format.md are read with a SchemaRecorder, which collects each key's
// rule as the reader states it (schema_recorder.hpp), and the docs' key tables describe each key.
// Draft-07 because editors support it best; nested mappings refuse unknown keys
// (additionalProperties: false) as the reader does.
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/scene_format_doc.hpp"

namespace rift {

struct SceneSchema {
  std::string json;                   // the schema, indented by 2, ending with a newline
  size_t keys = 0;                    // key paths it describes (fluid.mesh's keys count once, as mesh's)
  std::vector<std::string> problems;  // diagnostics of the complete examples (none in a consistent build)
};

// The schema from `doc`, the text of docs/scene-format.md (by default the copy built into the binary).
SceneSchema scene_schema(std::string_view doc = scene_format_doc());

}  // namespace rift
