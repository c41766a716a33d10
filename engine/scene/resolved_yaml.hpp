#pragma once
// The complete scene as YAML: every key the reader read, in reading order, with the value it took (the
// file's, an override's or the default; resolved_scene.hpp), numbers printed so they read back
// bit-identical. Reading it back gives the same Scene and the same hash, so it is what a run records to
// say exactly what it ran.
#include <string>
#include <string_view>

#include "engine/scene/resolved_scene.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

// `read`: what the scene's readers read (ReadContext::resolved).
std::string emit_resolved_yaml(const ResolvedNode& read);

// FNV-1a 64 of `text` as 16 lowercase hex digits. Identifies a resolved scene; not a security hash.
std::string fnv1a64_hex(std::string_view text);

// Scene::hash: fnv1a64_hex of the resolved YAML followed by a line per mesh file with the FNV-1a 64 of
// its bytes, so a scene whose mesh file changed at the same path hashes differently. The same as
// fnv1a64_hex(resolved_yaml) for a scene without mesh files.
std::string scene_hash(const Scene& scene);

}  // namespace rift
