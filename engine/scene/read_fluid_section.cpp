// fluid: incompressible Navier-Stokes (systems/fluid): material, time scheme, solver controls, body
// force, initial velocity and boundary conditions on named mesh surfaces, optionally its own mesh.
#include "engine/scene/scene_names.hpp"
#include "engine/scene/scene_sections.hpp"

namespace rift {
namespace {

// FluidBoundarySpec::Kind order.
constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};
constexpr std::array<std::string_view, 2> kSchemes{"backward_euler", "crank_nicolson"};
constexpr std::array<std::string_view, 2> kSubscales{"quasi_static", "dynamic"};

// fluid.adapt's own keys: how often the mesh is remade, and around which parts of the solid's surface.
FluidAdaptSpec read_adapt(MapReader& a) {
  FluidAdaptSpec adapt{a.integer("interval", IntRule{0, INT32_MAX}, 0)};
  adapt.boundary = adapt.notch = adapt.fracture = false;
  for (const std::string& name : a.string_list("surfaces", {"boundary", "notch", "fracture"})) {
    if (name == "boundary")
      adapt.boundary = true;
    else if (name == "notch")
      adapt.notch = true;
    else if (name == "fracture")
      adapt.fracture = true;
    else
      a.error("surfaces",
              "a list of boundary, notch and fracture (the parts of the solid's surface to refine at)");
  }
  a.finish();
  return adapt;
}

// Keys that apply to one boundary type only are forbidden for the others (as in the solid section).
FluidBoundarySpec read_boundary(MapReader& b) {
  using Kind = FluidBoundarySpec::Kind;
  FluidBoundarySpec bc;
  bc.surface = b.string("surface", std::nullopt);
  bc.kind = b.choice("type", scene_names::kFluidBoundary, std::optional<Kind>());
  if (!b.ok("type")) {  // which keys apply is unknown: accept them unread rather than guess
    for (auto key : {"direction", "value", "parabolic"}) b.declare(key);
    b.finish();
    return bc;
  }
  const std::string for_type = "for type " + std::string(name_of(scene_names::kFluidBoundary, bc.kind));
  TimeFunction one;
  one.value = 1.0;
  if (bc.kind == Kind::velocity) {
    bc.direction = b.vec3("direction", any_real("m/s"), std::nullopt);
    bc.function = b.time_function("value", "", one);  // dimensionless: scales `direction`
    for (size_t axis : b.choice_list("parabolic", kAxes, {}, 0)) bc.parabolic[axis] = true;
  } else {
    b.forbid("direction", for_type);
    b.forbid("parabolic", for_type);
    if (bc.kind == Kind::pressure)
      bc.function = b.time_function("value", "Pa", std::nullopt);
    else
      b.forbid("value", for_type + (bc.kind == Kind::outflow ? " (p = 0 there)" : ""));
  }
  b.finish();
  return bc;
}

}  // namespace

FluidSpec read_fluid_section(MapReader& sec, const std::string& base_dir) {
  FluidSpec f;
  static const std::string kMeshDoc = "mesh";  // the same keys as the top-level mesh section
  if (sec.has("mesh")) {
    MapReader m = sec.section("mesh", false, &kMeshDoc);
    f.mesh = read_mesh_section(m, base_dir);
  } else {
    sec.unused().section("mesh", false, &kMeshDoc);  // its keys are the top-level mesh's
  }
  f.density = sec.real("density", positive("kg/m^3"), std::nullopt);
  f.viscosity = sec.real("viscosity", positive("Pa s"), std::nullopt);
  f.dt = sec.real("dt", positive("s"), std::nullopt);
  // theta or scheme, not both; the one not read is read through sec.unused(), for its rule.
  const auto theta = [](auto&& r) { return r.real("theta", RealRule{"", 0.5, 1.0, false, false}, 1.0); };
  const auto scheme = [](auto&& r) { return r.choice("scheme", kSchemes, 0) == 0 ? 1.0 : 0.5; };
  if (sec.has("theta") && sec.has("scheme")) {
    sec.error("scheme", "either theta or scheme, not both");
    theta(sec.unused());
    scheme(sec.unused());
  } else if (sec.has("theta")) {
    f.theta = theta(sec);
    scheme(sec.unused());
  } else {
    f.theta = scheme(sec);
    theta(sec.unused());
  }
  f.convection = sec.boolean("convection", true);
  f.supg = sec.boolean("supg", true);
  f.dynamic_subscale = sec.choice("pressure_subscale", kSubscales, 0) == 1;
  f.coupling =
      sec.choice("coupling", scene_names::kPressureCoupling, std::optional(FluidSpec::Coupling::schur_gmres));
  f.picard_max_iterations = static_cast<int>(sec.integer("picard_max_iterations", IntRule{1, 1000}, 20));
  f.picard_tolerance = sec.real("picard_tolerance", positive(""), 1e-6);
  f.on_picard_failure = sec.choice("on_picard_failure", scene_names::kOnPicardFailure,
                                   std::optional(FluidSpec::OnPicardFailure::stop));
  f.velocity_tolerance = sec.real("velocity_tolerance", RealRule{"", 0.0, 1.0, true, true}, 1e-10);
  f.velocity_max_iterations =
      static_cast<int>(sec.integer("velocity_max_iterations", IntRule{1, 1000000}, 2000));
  f.schur_tolerance = sec.real("schur_tolerance", RealRule{"", 0.0, 1.0, true, true}, 1e-8);
  f.schur_max_iterations = static_cast<int>(sec.integer("schur_max_iterations", IntRule{1, 100000}, 200));
  f.schur_restart = static_cast<int>(sec.integer("schur_restart", IntRule{1, 1000}, 100));
  f.pressure_tolerance = sec.real("pressure_tolerance", RealRule{"", 0.0, 1.0, true, true}, 1e-8);
  f.pressure_max_iterations =
      static_cast<int>(sec.integer("pressure_max_iterations", IntRule{1, 100000}, 200));
  f.body_force = sec.vec3("body_force", any_real("N/m^3"), std::array<double, 3>{});
  f.initial_velocity = sec.vec3("initial_velocity", any_real("m/s"), std::array<double, 3>{});
  f.initial_pressure = sec.real("initial_pressure", any_real("Pa"), 0.0);
  auto boundaries = sec.section_list("boundaries", 1);
  for (auto& b : boundaries) f.boundaries.push_back(read_boundary(b));
  // One condition per surface: two on one surface would silently let the later one win.
  for (size_t i = 0; i < boundaries.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (boundaries[i].ok("surface") && boundaries[j].ok("surface") &&
          f.boundaries[i].surface == f.boundaries[j].surface) {
        boundaries[i].error("surface", "a surface no other fluid boundary names (also in " +
                                           sec.key_path("boundaries") + "[" + std::to_string(j) + "])");
        break;
      }
  if (sec.has("adapt")) {
    MapReader a = sec.section("adapt", false);
    f.adapt = read_adapt(a);
    // It remakes the mesh with the box generator's sizing, measured from the solid's surface.
    const MeshGenerateSpec* g = f.mesh && f.mesh->generate ? &*f.mesh->generate : nullptr;
    if (!g || g->shape != MeshGenerateSpec::Shape::box || g->cells || !g->notches.empty())
      sec.error(
          f.mesh ? "mesh" : "adapt",
          "with fluid.adapt, a fluid.mesh.generate box with size_min and size_max and no cells or notches "
          "(the adaptive mesh is that box, its size_min at the solid's surface)");
  } else {
    MapReader unused = sec.unused().section("adapt", false);
    read_adapt(unused);
  }
  sec.finish();
  return f;
}

FluidSolidSpec read_fluid_solid_section(MapReader& sec) {
  FluidSolidSpec c;
  c.force = sec.choice("force", scene_names::kCouplingForce, std::optional(FluidSolidSpec::Force::volume));
  c.substeps = sec.integer("substeps", IntRule{0, INT32_MAX}, 0);
  if (sec.has("relaxation_time")) {
    c.relaxation_time = sec.real("relaxation_time", positive("s"), std::nullopt);
    sec.forbid("beta",
               "with fluid_solid.relaxation_time, which sets the absorption itself (beta = fluid.dt / "
               "relaxation_time)");
    sec.unused().real("beta", positive(""), 1.0);  // its rule, for the scenes that give beta
  } else {
    c.beta = sec.real("beta", positive(""), 1.0);
    sec.unused().real("relaxation_time", positive("s"), std::nullopt);
  }
  c.added_mass = sec.real("added_mass", non_negative(""), 0.0);
  c.dilatation = sec.boolean("dilatation", false);
  c.continuity =
      sec.choice("continuity", scene_names::kContinuity, std::optional(FluidSolidSpec::Continuity::mixture));
  const auto inlet = [](auto&& r) { return r.vec3("network_inlet", any_real("m"), std::nullopt); };
  const auto extent = [](auto&& r) {
    return r.vec3("network_inlet_extent", non_negative("m"), std::array<double, 3>{});
  };
  if (sec.has("network_inlet")) {
    c.network_inlet = inlet(sec);
    c.network_inlet_extent = extent(sec);
  } else {
    inlet(sec.unused());
    sec.forbid("network_inlet_extent",
               "it sizes the region around fluid_solid.network_inlet, which is absent");
    extent(sec.unused());  // its rule, for the scenes with a network_inlet
  }
  c.coupling = sec.choice("coupling", scene_names::kWindowCoupling,
                          std::optional(FluidSolidSpec::Coupling::sequential));
  sec.finish();
  return c;
}

}  // namespace rift
