#pragma once
// The fields a probe can read (scene `probes[i].field`) and their components, by name. The scene reader
// checks a probe against this table; the model named by the field's prefix reads it (systems/probes.hpp).
#include <array>
#include <span>
#include <string_view>

namespace rift {

struct ProbeField {
  std::string_view name;                         // "<model>.<field>"
  std::span<const std::string_view> components;  // the first is the default
  std::string_view unit;
  std::string_view meaning;
};

inline constexpr std::array<std::string_view, 4> kProbeVectorComponents{"x", "y", "z", "magnitude"};
inline constexpr std::array<std::string_view, 1> kProbeScalarComponents{"value"};
// Voigt order, as the solid stores its stress.
inline constexpr std::array<std::string_view, 6> kProbeStressComponents{"xx", "yy", "zz", "xy", "yz", "zx"};

inline constexpr std::array<ProbeField, 5> kProbeFields{{
    {"fluid.velocity", kProbeVectorComponents, "m/s", "the fluid's velocity (P1), at points fixed in space"},
    {"fluid.pressure", kProbeScalarComponents, "Pa", "the fluid's pressure (P1), at points fixed in space"},
    {"solid.displacement", kProbeVectorComponents, "m",
     "x - x0 (P1 in the tet holding the point in the reference configuration: the probe moves with the "
     "rock)"},
    {"solid.velocity", kProbeVectorComponents, "m/s",
     "the solid's velocity (the central difference's, at t - dt/2), read as solid.displacement"},
    {"solid.stress", kProbeStressComponents, "Pa", "the Cauchy stress of the tet holding the point (P0)"},
}};

inline const ProbeField* find_probe_field(std::string_view name) {
  for (const ProbeField& f : kProbeFields)
    if (f.name == name) return &f;
  return nullptr;
}

}  // namespace rift
