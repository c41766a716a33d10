// solid.fracture (where joints exist, how they integrate, cracks present at t = 0),
// solid.materials[i].fracture (joint properties), solid.contact and solid.initial_stress (in-situ state).
#include <fmt/format.h>

#include <cmath>

#include "engine/scene/scene_sections.hpp"

namespace rift {

namespace {
constexpr std::array<std::string_view, 2> kSoftening{"energy_exact", "y_compatible"};

CrackPlaneSpec read_crack_plane(MapReader& c) {
  CrackPlaneSpec crack;
  crack.point = c.vec3("point", any_real("m"), std::nullopt);
  crack.normal = c.vec3("normal", any_real(""), std::nullopt);
  const auto& n = crack.normal;
  if (c.ok("normal") && !(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0))
    c.error("normal", "a non-zero vector");
  crack.radius = c.optional_real("radius", positive("m"));
  c.finish();
  return crack;
}

}  // namespace

FractureMaterialSpec read_fracture_material(MapReader& f, double young) {
  FractureMaterialSpec m;
  m.tensile_strength = f.real("tensile_strength", positive("Pa"), std::nullopt);
  m.cohesion = f.real("cohesion", positive("Pa"), std::nullopt);
  m.friction_angle = f.real("friction_angle", RealRule{"degrees", 0.0, 90.0, false, true}, std::nullopt);
  m.residual_friction = f.real("residual_friction", non_negative(""), 0.0);
  m.G_I = f.real("G_I", positive("J/m^2"), std::nullopt);
  m.G_II = f.real("G_II", positive("J/m^2"), std::nullopt);
  // 10 E: the joints then soften the bulk by about 9 % and cut the stable step by about 3 (femdem.md 1d).
  m.penalty = f.real("penalty", positive("Pa"), 10.0 * young);
  f.default_varies("penalty");
  // A joint opens by 2 f_t h / p at its peak (and slips 2 c h / p): below 1e-12 of its size h that is the
  // round-off of the node positions, and the law's scales (1 / opening) overflow. Such a joint breaks by
  // round-off, so the strengths must be at least 5e-13 of the penalty.
  struct Strength {
    const char* key;
    double value;
    const char* symbol;
  };
  for (const Strength& s :
       {Strength{"tensile_strength", m.tensile_strength, "f_t"}, Strength{"cohesion", m.cohesion, "c"}}) {
    if (f.ok(s.key) && f.ok("penalty") && !(s.value >= 5e-13 * m.penalty))
      f.error(
          s.key,
          fmt::format("at least 5e-13 x the penalty ({:.3g} Pa), so that a joint's peak opening 2 {} h / p "
                      "is above the round-off of node positions",
                      5e-13 * m.penalty, s.symbol),
          "lower the penalty or raise the strength; for a material that should not hold, leave its tets out "
          "of solid.fracture's regions");
  }
  if (f.ok("residual_friction") && f.ok("friction_angle") &&
      m.residual_friction > std::tan(m.friction_angle * M_PI / 180.0) + 1e-12)
    f.error("residual_friction",
            "a residual friction coefficient <= tan(friction_angle) = " +
                std::to_string(std::tan(m.friction_angle * M_PI / 180.0)),
            "a softened joint cannot be stronger in friction than the intact envelope");
  f.finish();
  return m;
}

FractureSpec read_fracture_section(MapReader& f) {
  FractureSpec spec;
  spec.regions = f.string_list("regions", {"all"});
  const bool has_min = f.has("box_min"), has_max = f.has("box_max");
  if (has_min) spec.box_min = f.vec3("box_min", any_real("m"), std::nullopt);
  if (has_max) spec.box_max = f.vec3("box_max", any_real("m"), std::nullopt);
  if (has_min != has_max) {
    f.error(has_min ? "box_min" : "box_max", "box_min and box_max together (or neither)");
  } else if (has_min && f.ok("box_min") && f.ok("box_max")) {
    for (int a = 0; a < 3; ++a)
      if (!((*spec.box_max)[a] > (*spec.box_min)[a])) {
        f.error("box_max", "each component greater than box_min's");
        break;
      }
  }
  const int64_t points = f.integer("integration_points", IntRule{3, 7}, 3);
  if (f.ok("integration_points") && points != 3 && points != 7)
    f.error("integration_points", "3 or 7 (the triangle rules of the joint)");
  spec.integration_points = static_cast<int>(points);
  spec.y_compatible = f.choice("softening", kSoftening, 0) == 1;
  for (auto& c : f.section_list("initial_cracks", 0)) spec.initial_cracks.push_back(read_crack_plane(c));
  const auto crack_pressure = [](auto&& r) { return r.time_function("crack_pressure", "Pa", std::nullopt); };
  if (f.has("crack_pressure"))
    spec.crack_pressure = crack_pressure(f);
  else
    crack_pressure(f.unused());  // known with its rule; absent: no crack pressure
  f.finish();
  return spec;
}

ContactSpec read_contact_section(MapReader& c) {
  ContactSpec spec;
  spec.penalty = c.optional_real("penalty", positive("Pa"));
  spec.friction = c.real("friction", non_negative(""), 0.0);
  spec.tangential_penalty = c.real("tangential_penalty", positive(""), 0.1);
  spec.damping = c.real("damping", RealRule{"", 0.0, 1.0, false, false}, 0.0);
  spec.buffer = c.optional_real("buffer", positive("m"));
  c.finish();
  return spec;
}

InitialStressSpec read_initial_stress_section(MapReader& s) {
  InitialStressSpec spec;
  spec.principal = s.vec3("principal", any_real("Pa"), std::nullopt);
  spec.direction_1 = s.vec3("direction_1", any_real(""), std::array<double, 3>{1, 0, 0});
  spec.direction_2 = s.vec3("direction_2", any_real(""), std::array<double, 3>{0, 1, 0});
  auto norm = [](const std::array<double, 3>& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  };
  const double n1 = norm(spec.direction_1), n2 = norm(spec.direction_2);
  if (s.ok("direction_1") && !(n1 > 0)) s.error("direction_1", "a non-zero vector");
  if (s.ok("direction_2") && !(n2 > 0)) s.error("direction_2", "a non-zero vector");
  if (n1 > 0 && n2 > 0 && s.ok("direction_1") && s.ok("direction_2")) {
    const auto& a = spec.direction_1;
    const auto& b = spec.direction_2;
    if (std::abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) > 1e-9 * n1 * n2)
      s.error("direction_2", "a vector orthogonal to direction_1 (principal directions)");
  }
  s.finish();
  return spec;
}

}  // namespace rift
