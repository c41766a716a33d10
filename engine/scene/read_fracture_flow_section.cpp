// fracture_flow: the fluid in the cracks (docs/scene-format.md, docs/hydraulic-fracture.md).
#include <array>
#include <string_view>

#include "engine/scene/scene_names.hpp"
#include "engine/scene/scene_sections.hpp"

namespace rift {

FractureFlowSpec read_fracture_flow_section(MapReader& f, bool pressure_from_fluid) {
  FractureFlowSpec spec;
  spec.eos.density0 = f.real("density", positive("kg/m^3"), 1000.0);
  spec.viscosity = f.real("viscosity", non_negative("Pa s"), 1.0e-3);
  spec.eos.bulk_modulus = f.real("bulk_modulus", positive("Pa"), 2.2e9);
  spec.eos.pressure0 = f.real("reference_pressure", any_real("Pa"), 0.0);
  spec.aperture_floor = f.real("aperture_floor", positive("m"), 1.0e-6);
  spec.lag_pressure = f.real("lag_pressure", any_real("Pa"), 0.0);
  spec.initial_pressure = f.real("initial_pressure", any_real("Pa"), 0.0);
  spec.interval = f.integer("interval", IntRule{1, 1000000}, 1);
  spec.solver =
      f.choice("solver", scene_names::kNetworkSolver, std::optional(FractureFlowSpec::Solver::automatic));
  spec.wet_damage = f.real("wet_damage", RealRule{"", 0.0, 1.0, true, false}, 1.0);
  if (f.ok("lag_pressure") && f.ok("bulk_modulus") && f.ok("reference_pressure") &&
      !(spec.lag_pressure > spec.eos.pressure0 - spec.eos.bulk_modulus))
    f.error("lag_pressure", "a pressure above reference_pressure - bulk_modulus (where the density is zero)");
  MapReader well = f.section("injection", true);
  spec.point = well.vec3("point", any_real("m"), std::nullopt);
  // The one not given is read through well.unused(), for its rule.
  const auto rate = [](auto&& r) { return r.time_function("rate", "m^3/s", std::nullopt); };
  const auto pressure = [](auto&& r) { return r.time_function("pressure", "Pa", std::nullopt); };
  const bool by_rate = well.has("rate"), by_pressure = well.has("pressure");
  if (by_rate)
    spec.rate = rate(well);
  else
    rate(well.unused());
  if (by_pressure)
    spec.pressure = pressure(well);
  else
    pressure(well.unused());
  spec.pressure_from_fluid = pressure_from_fluid;
  if (pressure_from_fluid && (by_rate || by_pressure))
    well.error(by_rate ? "rate" : "pressure",
               "neither rate nor pressure with fluid_solid.network_inlet (the surrounding fluid sets the "
               "well's pressure)",
               by_rate ? "a rate" : "a pressure");
  else if (!pressure_from_fluid && by_rate == by_pressure)
    well.error(by_rate ? "pressure" : "rate",
               "one of rate (m^3/s) and pressure (Pa): the well is driven by one",
               by_rate ? "both are given" : "neither is given");
  const auto surfaces = [](auto&& r) { return r.string_list("surfaces", {}); };
  if (well.has("surfaces")) {  // a borehole: the wall is the well (absent: the nearest crack vertex)
    spec.well_surfaces = surfaces(well);
    if (well.ok("surfaces") && spec.well_surfaces.empty())
      well.error("surfaces", "a list of at least one surface name (the well's wall)", "an empty list");
  } else {
    surfaces(well.unused());
  }
  spec.well_volume = well.real("well_volume", non_negative("m^3"), 0.0);
  spec.well_compliance = well.real("well_compliance", non_negative("m^3/Pa"), 0.0);
  well.finish();
  spec.vent_pressure = f.optional_real("vent_pressure", any_real("Pa"));
  const auto vent_surfaces = [](auto&& r) { return r.string_list("vent_surfaces", {}); };
  if (f.has("vent_surfaces"))  // absent: every surface of the mesh
    spec.vent_surfaces = vent_surfaces(f);
  else
    vent_surfaces(f.unused());
  spec.leak_off = f.real("leak_off", non_negative("m/s^0.5"), 0.0);
  spec.spurt = f.real("spurt", non_negative("m"), 0.0);
  f.finish();
  return spec;
}

}  // namespace rift
