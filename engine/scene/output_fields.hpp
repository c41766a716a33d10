#pragma once
// The field names a scene may list under output.fields. Systems add theirs here; the scene reader,
// its "did you mean" and docs/scene-format.md all follow this one list.
#include <algorithm>
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace rift {

inline constexpr std::array<std::string_view, 20> kOutputFieldNames{
    "displacement", "velocity",       "force",         "stress",   "principal_stress",
    "region",       "material",       "damage",        "opening",  "slip",
    "broken",       "energy",         "contact_force", "pressure", "divergence",
    "cfl",          "solid_fraction", "fluid_force",   "aperture", "wetting_time"};

// Whether an output that asked for `fields` (empty: every field) wants the field `name`.
inline bool wants_field(const std::vector<std::string>& fields, std::string_view name) {
  return fields.empty() || std::find(fields.begin(), fields.end(), name) != fields.end();
}

}  // namespace rift
