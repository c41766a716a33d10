#pragma once
// The field names a scene may list under output.fields. Systems add theirs here; the scene reader,
// its "did you mean" and docs/scene-format.md all follow this one list.
#include <array>
#include <string_view>

namespace rift {

inline constexpr std::array<std::string_view, 16> kOutputFieldNames{
    "displacement", "velocity", "force",  "stress", "principal_stress", "region",   "material",   "damage",
    "opening",      "slip",     "broken", "energy", "contact_force",    "pressure", "divergence", "cfl"};

}  // namespace rift
