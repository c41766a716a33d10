// solid: materials (elastic constants per mesh region), boundary conditions and gravity.
#include <map>

#include "engine/scene/scene_names.hpp"
#include "engine/scene/scene_sections.hpp"

namespace rift {
namespace {

constexpr std::array<std::string_view, 3> kComponents{"x", "y", "z"};

MaterialSpec read_material(MapReader& m) {
  MaterialSpec mat;
  mat.name = m.string("name", std::nullopt);
  mat.regions = m.string_list("regions", {"all"});
  mat.density = m.real("density", positive("kg/m^3"), std::nullopt);
  mat.young = m.real("young", positive("Pa"), std::nullopt);
  mat.poisson = m.real("poisson", RealRule{"", 0.0, 0.5, false, true}, std::nullopt);
  mat.damping = m.real("damping", RealRule{"", 0.0, 1.0, false, false}, 0.0);
  if (m.has("fracture")) {
    MapReader f = m.section("fracture", false);
    mat.fracture = read_fracture_material(f, mat.young);
  } else {
    MapReader unused = m.unused().section("fracture", false);
    read_fracture_material(unused, mat.young);
  }
  m.finish();
  return mat;
}

// Keys that apply to only some boundary types are forbidden for the others, so a pressure boundary
// with a `direction` is an error rather than a silently ignored vector.
SolidBoundarySpec read_boundary(MapReader& b) {
  using Kind = SolidBoundarySpec::Kind;
  SolidBoundarySpec bc;
  // A surface or a node set's box; the other form is read through b.unused(), so that it is known with
  // its rule.
  const auto corner = [](auto&& r, const char* key) { return r.vec3(key, any_real("m"), std::nullopt); };
  const auto surface = [](auto&& r) { return r.string("surface", std::nullopt); };
  const bool by_box = b.has("box_min") || b.has("box_max");
  if (by_box) {
    bc.box_min = corner(b, "box_min");
    bc.box_max = corner(b, "box_max");
    if (b.has("surface")) b.error("surface", "either surface or box_min/box_max (a node set), not both");
    surface(b.unused());
  } else {
    bc.surface = surface(b);
    corner(b.unused(), "box_min");
    corner(b.unused(), "box_max");
  }
  bc.kind = b.choice("type", scene_names::kSolidBoundary, std::optional<Kind>());
  if (!b.ok("type")) {  // which keys apply is unknown: accept them unread rather than guess
    for (auto key : {"components", "direction", "value"}) b.declare(key);
    b.finish();
    return bc;
  }
  const std::string for_type = "for type " + std::string(name_of(scene_names::kSolidBoundary, bc.kind));
  if (bc.kind == Kind::fixed || bc.kind == Kind::velocity) {
    std::array<bool, 3> on{};
    for (size_t axis : b.choice_list("components", kComponents, {0, 1, 2}, 1)) on[axis] = true;
    bc.components = on;
  } else {
    b.forbid("components", for_type + " (it loads every axis)");
  }
  if (bc.kind == Kind::velocity) {
    bc.direction = b.vec3("direction", any_real("m/s"), std::nullopt);
  } else if (bc.kind == Kind::traction) {
    bc.direction = b.vec3("direction", any_real("Pa"), std::nullopt);
  } else {
    b.forbid("direction", for_type);
  }
  if (by_box && bc.kind != Kind::fixed && bc.kind != Kind::velocity && b.ok("type"))
    b.error("type", "fixed or velocity for a node set (box_min/box_max): loads need surface faces");
  if (bc.kind == Kind::fixed) {
    b.forbid("value", for_type);
  } else if (bc.kind == Kind::fluid_pressure) {
    b.forbid("value", for_type + " (the fluid gives the pressure)");
  } else if (bc.kind == Kind::pressure) {
    bc.function = b.time_function("value", "Pa", std::nullopt);
  } else if (bc.kind == Kind::in_situ) {
    TimeFunction one;
    one.value = 1.0;
    bc.function = b.time_function("value", "", one);  // dimensionless: scales initial_stress . n
  } else {
    TimeFunction one;
    one.value = 1.0;
    bc.function = b.time_function("value", "", one);  // dimensionless: scales `direction`
  }
  b.finish();
  return bc;
}

void check_unique_names(MapReader& solid, std::vector<MapReader>& readers,
                        const std::vector<MaterialSpec>& mats) {
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < mats.size(); ++i) {
    if (!readers[i].ok("name")) continue;
    auto [it, inserted] = seen.emplace(mats[i].name, i);
    if (!inserted)
      readers[i].error("name", "a name no other material has (also used by " + solid.key_path("materials") +
                                   "[" + std::to_string(it->second) + "])");
  }
}

}  // namespace

SolidSpec read_solid_section(MapReader& sec) {
  SolidSpec solid;
  solid.gravity = sec.vec3("gravity", any_real("m/s^2"), std::array<double, 3>{});
  solid.mass_damping = sec.time_function("mass_damping", "1/s", TimeFunction{});
  if (solid.mass_damping.lowest() < 0.0)
    sec.error("mass_damping",
              "a damping >= 0 1/s at every time (a number, a ramp that stays >= 0, or a table of "
              "values >= 0)");
  solid.mass_scaling_step = sec.real("mass_scaling_step", non_negative("s"), 0.0);
  solid.fused_tet_pass = sec.boolean("fused_tet_pass", true);
  auto materials = sec.section_list("materials", 1);
  for (auto& m : materials) solid.materials.push_back(read_material(m));
  check_unique_names(sec, materials, solid.materials);
  for (auto& v : sec.section_list("initial_velocity", 0)) {
    InitialVelocitySpec iv;
    iv.regions = v.string_list("regions", {"all"});
    iv.velocity = v.vec3("velocity", any_real("m/s"), std::nullopt);
    v.finish();
    solid.initial_velocity.push_back(iv);
  }
  auto boundaries = sec.section_list("boundaries", 0);
  for (auto& b : boundaries) solid.boundaries.push_back(read_boundary(b));
  if (sec.has("fracture")) {
    MapReader f = sec.section("fracture", false);
    solid.fracture = read_fracture_section(f);
  } else {
    MapReader unused = sec.unused().section("fracture", false);
    read_fracture_section(unused);
  }
  if (sec.has("contact")) {
    MapReader c = sec.section("contact", false);
    solid.contact = read_contact_section(c);
  } else {
    MapReader unused = sec.unused().section("contact", false);
    read_contact_section(unused);
  }
  if (sec.has("initial_stress")) {
    MapReader s = sec.section("initial_stress", false);
    solid.initial_stress = read_initial_stress_section(s);
  } else {
    MapReader unused = sec.unused().section("initial_stress", false);
    read_initial_stress_section(unused);
  }
  for (size_t i = 0; i < boundaries.size(); ++i)
    if (solid.boundaries[i].kind == SolidBoundarySpec::Kind::in_situ && !solid.initial_stress &&
        boundaries[i].ok("type"))
      boundaries[i].error("type", "in_situ only with a solid.initial_stress section",
                          "add solid.initial_stress, or use traction/pressure");
  sec.finish();
  return solid;
}

}  // namespace rift
