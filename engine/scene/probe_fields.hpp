#pragma once
// The fields a probe can read (scene `probes[i].field`) and their components, by name. The scene reader
// checks a probe against this table; the model named by the field's prefix reads it
// (systems/probe_model.hpp).
#include <array>
#include <span>
#include <string_view>

namespace rift {

struct ProbeField {
  std::string_view name;                         // "<model>.<field>"
  std::span<const std::string_view> components;  // the first is the default
  std::string_view unit;                         // of the field (a probe's reading is factor x the field)
};

inline constexpr std::array<std::string_view, 4> kProbeVectorComponents{"x", "y", "z", "magnitude"};
inline constexpr std::array<std::string_view, 1> kProbeScalarComponents{"value"};
// Voigt order, as the solid stores its stress.
inline constexpr std::array<std::string_view, 6> kProbeStressComponents{"xx", "yy", "zz", "xy", "yz", "zx"};

inline constexpr std::array<ProbeField, 5> kProbeFields{{
    {"fluid.velocity", kProbeVectorComponents, "m/s"},
    {"fluid.pressure", kProbeScalarComponents, "Pa"},
    {"solid.displacement", kProbeVectorComponents, "m"},
    {"solid.velocity", kProbeVectorComponents, "m/s"},
    {"solid.stress", kProbeStressComponents, "Pa"},
}};

inline const ProbeField* find_probe_field(std::string_view name) {
  for (const ProbeField& f : kProbeFields)
    if (f.name == name) return &f;
  return nullptr;
}

}  // namespace rift
