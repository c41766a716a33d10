#include "engine/scene/resolved_yaml.hpp"

#include <cstdio>

#include "engine/core/fnv1a.hpp"
#include "engine/scene/number_text.hpp"
#include "engine/scene/scene_names.hpp"

namespace rift {
namespace {

// Strings are always double-quoted so no name can turn into a number, boolean or null on re-reading.
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string vec3(const std::array<double, 3>& v) {
  return "[" + yaml_real(v[0]) + ", " + yaml_real(v[1]) + ", " + yaml_real(v[2]) + "]";
}

// Appends "indent key: value" lines.
class Lines {
 public:
  void line(int indent, std::string_view key, std::string_view value = {}) {
    text_.append(static_cast<size_t>(indent) * 2, ' ');
    text_ += key;
    text_ += ':';
    if (!value.empty()) {
      text_ += ' ';
      text_ += value;
    }
    text_ += '\n';
  }
  // The first key of a list item: "- key: value" at `indent`.
  void item(int indent, std::string_view key, std::string_view value) {
    text_.append(static_cast<size_t>(indent) * 2, ' ');
    text_ += "- ";
    line(0, key, value);
  }
  std::string& text() { return text_; }

 private:
  std::string text_;
};

void emit_time_function(Lines& o, int indent, std::string_view key, const TimeFunction& f) {
  switch (f.kind) {
    case TimeFunction::Kind::constant:
      o.line(indent, key, yaml_real(f.value));
      return;
    case TimeFunction::Kind::ramp:
      o.line(indent, key);
      o.line(indent + 1, "ramp");
      o.line(indent + 2, "value", yaml_real(f.value));
      o.line(indent + 2, "start_time", yaml_real(f.start_time));
      o.line(indent + 2, "rate", yaml_real(f.rate));
      o.line(indent + 2, "limit", f.has_limit ? yaml_real(f.limit) : "null");
      return;
    case TimeFunction::Kind::table: {
      std::string rows;
      for (const auto& [t, v] : f.points)
        rows += (rows.empty() ? "[" : ", [") + yaml_real(t) + ", " + yaml_real(v) + "]";
      o.line(indent, key);
      o.line(indent + 1, "table", "[" + rows + "]");
      return;
    }
  }
}

void emit_time(Lines& o, const TimeSpec& t) {
  o.line(0, "time");
  o.line(1, "end", yaml_real(t.end));
  o.line(1, "dt", t.dt ? yaml_real(*t.dt) : "null");
  o.line(1, "safety", yaml_real(t.safety));
  o.line(1, "allow_unstable_dt", t.allow_unstable_dt ? "true" : "false");
}

void emit_notch(Lines& o, const NotchSpec& n, int i) {
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  o.item(i + 3, "shape", name_of(scene_names::kNotchShape, n.shape));
  o.line(i + 4, "face", n.face);
  o.line(i + 4, "opening_axis", kAxes[n.opening_axis]);
  o.line(i + 4, "center", yaml_real(n.center));
  o.line(i + 4, "depth", yaml_real(n.depth));
  o.line(i + 4, "opening", yaml_real(n.opening));
  o.line(i + 4, "name", quoted(n.name));
}

// At `indent` (0: the top-level mesh, 1: fluid.mesh).
void emit_mesh(Lines& o, const MeshSpec& m, int indent = 0) {
  const int i = indent;
  o.line(i, "mesh");
  if (m.file) o.line(i + 1, "file", quoted(*m.file));
  o.line(i + 1, "scale", yaml_real(m.scale));
  if (m.file) o.line(i + 1, "max_file_bytes", std::to_string(m.max_file_bytes));
  if (!m.generate) return;
  const MeshGenerateSpec& g = *m.generate;
  o.line(i + 1, "max_elements", std::to_string(g.max_elements));
  o.line(i + 1, "generate");
  if (g.shape == MeshGenerateSpec::Shape::blocks) {
    o.line(i + 2, "blocks");
    for (const auto& b : g.blocks) {
      o.item(i + 3, "name", quoted(b.name));
      o.line(i + 4, "origin", vec3(b.origin));
      o.line(i + 4, "size", vec3(b.size));
      if (b.element_size)
        o.line(i + 4, "element_size", yaml_real(*b.element_size));
      else
        o.line(i + 4, "cells",
               "[" + std::to_string(b.cells[0]) + ", " + std::to_string(b.cells[1]) + ", " +
                   std::to_string(b.cells[2]) + "]");
    }
    return;  // a lattice: the mesher's keys do not apply (the reader forbids them)
  }
  const bool cylinder = g.shape == MeshGenerateSpec::Shape::cylinder;
  if (cylinder) {
    o.line(i + 2, "cylinder");
    o.line(i + 3, "diameter", yaml_real(g.cylinder.diameter));
    o.line(i + 3, "thickness", yaml_real(g.cylinder.thickness));
    o.line(i + 3, "load_arc", yaml_real(g.cylinder.load_arc));
  } else {
    o.line(i + 2, "box", vec3(g.size));
  }
  o.line(i + 2, "origin", vec3(g.origin));
  if (g.borehole) {  // a hole's lattice: the reader forbids the sizing keys
    o.line(i + 2, "borehole");
    o.line(i + 3, "axis_x", yaml_real(g.borehole->axis_x));
    o.line(i + 3, "axis_y", yaml_real(g.borehole->axis_y));
    o.line(i + 3, "radius", yaml_real(g.borehole->radius));
    o.line(i + 3, "size", yaml_real(g.borehole->size));
    o.line(i + 3, "growth", yaml_real(g.borehole->growth));
    return;
  }
  if (g.graded) {  // a graded lattice: the reader forbids the sizing keys
    o.line(i + 2, "graded");
    o.line(i + 3, "fine_min", vec3(g.graded->fine_min));
    o.line(i + 3, "fine_max", vec3(g.graded->fine_max));
    o.line(i + 3, "size", yaml_real(g.graded->size));
    o.line(i + 3, "growth", yaml_real(g.graded->growth));
    return;
  }
  if (g.cells) {  // a structured lattice: the reader forbids the sizing keys
    const auto& c = *g.cells;
    o.line(i + 2, "cells",
           "[" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + "]");
    return;
  }
  o.line(i + 2, "size_min", yaml_real(g.size_min));
  o.line(i + 2, "size_max", yaml_real(g.size_max));
  o.line(i + 2, "grading", yaml_real(g.grading));
  o.line(i + 2, "seed", std::to_string(g.seed));
  if (cylinder) return;  // notches are for boxes only (the reader forbids the key)
  o.line(i + 2, "notches", g.notches.empty() ? "[]" : "");
  for (const auto& n : g.notches) emit_notch(o, n, i);
}

void emit_material(Lines& o, const MaterialSpec& m) {
  std::string regions;
  for (const auto& r : m.regions) regions += (regions.empty() ? "" : ", ") + quoted(r);
  o.item(2, "name", quoted(m.name));
  o.line(3, "regions", "[" + regions + "]");
  o.line(3, "density", yaml_real(m.density));
  o.line(3, "young", yaml_real(m.young));
  o.line(3, "poisson", yaml_real(m.poisson));
  o.line(3, "damping", yaml_real(m.damping));
  if (!m.fracture) return;
  const FractureMaterialSpec& f = *m.fracture;
  o.line(3, "fracture");
  o.line(4, "tensile_strength", yaml_real(f.tensile_strength));
  o.line(4, "cohesion", yaml_real(f.cohesion));
  o.line(4, "friction_angle", yaml_real(f.friction_angle));
  o.line(4, "residual_friction", yaml_real(f.residual_friction));
  o.line(4, "G_I", yaml_real(f.G_I));
  o.line(4, "G_II", yaml_real(f.G_II));
  o.line(4, "penalty", yaml_real(f.penalty));
}

void emit_fracture(Lines& o, const FractureSpec& f) {
  std::string regions;
  for (const auto& r : f.regions) regions += (regions.empty() ? "" : ", ") + quoted(r);
  o.line(1, "fracture");
  o.line(2, "regions", "[" + regions + "]");
  if (f.box_min) o.line(2, "box_min", vec3(*f.box_min));
  if (f.box_max) o.line(2, "box_max", vec3(*f.box_max));
  o.line(2, "integration_points", std::to_string(f.integration_points));
  o.line(2, "softening", f.y_compatible ? "y_compatible" : "energy_exact");
  o.line(2, "initial_cracks", f.initial_cracks.empty() ? "[]" : "");
  for (const auto& c : f.initial_cracks) {
    o.item(3, "point", vec3(c.point));
    o.line(4, "normal", vec3(c.normal));
    o.line(4, "radius", c.radius ? yaml_real(*c.radius) : "null");
  }
}

void emit_contact(Lines& o, const ContactSpec& c) {
  o.line(1, "contact");
  o.line(2, "penalty", c.penalty ? yaml_real(*c.penalty) : "null");
  o.line(2, "friction", yaml_real(c.friction));
  o.line(2, "tangential_penalty", yaml_real(c.tangential_penalty));
  o.line(2, "damping", yaml_real(c.damping));
  o.line(2, "buffer", c.buffer ? yaml_real(*c.buffer) : "null");
}

void emit_initial_stress(Lines& o, const InitialStressSpec& s) {
  o.line(1, "initial_stress");
  o.line(2, "principal", vec3(s.principal));
  o.line(2, "direction_1", vec3(s.direction_1));
  o.line(2, "direction_2", vec3(s.direction_2));
}

// Only the keys that apply to the boundary's type, as the reader forbids the others.
void emit_boundary(Lines& o, const SolidBoundarySpec& b) {
  using Kind = SolidBoundarySpec::Kind;
  if (b.box_min) {
    o.item(2, "box_min", vec3(*b.box_min));
    o.line(3, "box_max", vec3(*b.box_max));
  } else {
    o.item(2, "surface", quoted(b.surface));
  }
  o.line(3, "type", name_of(scene_names::kSolidBoundary, b.kind));
  if (b.kind == Kind::fixed || b.kind == Kind::velocity) {
    std::string comps;
    for (int a = 0; a < 3; ++a)
      if (b.components[a]) comps += std::string(comps.empty() ? "" : ", ") + "xyz"[a];
    o.line(3, "components", "[" + comps + "]");
  }
  if (b.kind == Kind::velocity || b.kind == Kind::traction) o.line(3, "direction", vec3(b.direction));
  if (b.kind != Kind::fixed && b.kind != Kind::fluid_pressure) emit_time_function(o, 3, "value", b.function);
}

void emit_solid(Lines& o, const SolidSpec& s) {
  o.line(0, "solid");
  o.line(1, "gravity", vec3(s.gravity));
  emit_time_function(o, 1, "mass_damping", s.mass_damping);
  o.line(1, "mass_scaling_step", yaml_real(s.mass_scaling_step));
  o.line(1, "fused_tet_pass", s.fused_tet_pass ? "true" : "false");
  o.line(1, "materials");
  for (const auto& m : s.materials) emit_material(o, m);
  o.line(1, "initial_velocity", s.initial_velocity.empty() ? "[]" : "");
  for (const auto& v : s.initial_velocity) {
    std::string regions;
    for (const auto& r : v.regions) regions += (regions.empty() ? "" : ", ") + quoted(r);
    o.item(2, "regions", "[" + regions + "]");
    o.line(3, "velocity", vec3(v.velocity));
  }
  o.line(1, "boundaries", s.boundaries.empty() ? "[]" : "");
  for (const auto& b : s.boundaries) emit_boundary(o, b);
  if (s.fracture) emit_fracture(o, *s.fracture);
  if (s.contact) emit_contact(o, *s.contact);
  if (s.initial_stress) emit_initial_stress(o, *s.initial_stress);
}

void emit_fluid(Lines& o, const FluidSpec& f) {
  using Kind = FluidBoundarySpec::Kind;
  o.line(0, "fluid");
  if (f.mesh) emit_mesh(o, *f.mesh, 1);
  o.line(1, "density", yaml_real(f.density));
  o.line(1, "viscosity", yaml_real(f.viscosity));
  o.line(1, "dt", yaml_real(f.dt));
  o.line(1, "theta", yaml_real(f.theta));
  o.line(1, "convection", f.convection ? "true" : "false");
  o.line(1, "supg", f.supg ? "true" : "false");
  o.line(1, "pressure_subscale", f.dynamic_subscale ? "dynamic" : "quasi_static");
  o.line(1, "coupling", name_of(scene_names::kPressureCoupling, f.coupling));
  o.line(1, "picard_max_iterations", std::to_string(f.picard_max_iterations));
  o.line(1, "picard_tolerance", yaml_real(f.picard_tolerance));
  o.line(1, "on_picard_failure", name_of(scene_names::kOnPicardFailure, f.on_picard_failure));
  o.line(1, "velocity_tolerance", yaml_real(f.velocity_tolerance));
  o.line(1, "velocity_max_iterations", std::to_string(f.velocity_max_iterations));
  o.line(1, "schur_tolerance", yaml_real(f.schur_tolerance));
  o.line(1, "schur_max_iterations", std::to_string(f.schur_max_iterations));
  o.line(1, "schur_restart", std::to_string(f.schur_restart));
  o.line(1, "pressure_tolerance", yaml_real(f.pressure_tolerance));
  o.line(1, "pressure_max_iterations", std::to_string(f.pressure_max_iterations));
  o.line(1, "body_force", vec3(f.body_force));
  o.line(1, "initial_velocity", vec3(f.initial_velocity));
  o.line(1, "initial_pressure", yaml_real(f.initial_pressure));
  o.line(1, "boundaries");
  for (const auto& b : f.boundaries) {
    o.item(2, "surface", quoted(b.surface));
    o.line(3, "type", name_of(scene_names::kFluidBoundary, b.kind));
    if (b.kind == Kind::velocity) {
      o.line(3, "direction", vec3(b.direction));
      std::string axes;
      for (int a = 0; a < 3; ++a)
        if (b.parabolic[a]) axes += std::string(axes.empty() ? "" : ", ") + "xyz"[a];
      o.line(3, "parabolic", "[" + axes + "]");
    }
    if (b.kind == Kind::velocity || b.kind == Kind::pressure) emit_time_function(o, 3, "value", b.function);
  }
}

void emit_output(Lines& o, const OutputSpec& out) {
  std::string fields;
  for (const auto& f : out.fields) fields += (fields.empty() ? "" : ", ") + f;
  o.line(0, "output");
  o.line(1, "interval", yaml_real(out.interval));
  o.line(1, "fields", "[" + fields + "]");
  o.line(1, "surface", out.surface ? "true" : "false");
}

void emit_fluid_solid(Lines& o, const FluidSolidSpec& c) {
  o.line(0, "fluid_solid");
  o.line(1, "force", name_of(scene_names::kCouplingForce, c.force));
  o.line(1, "substeps", std::to_string(c.substeps));
  if (c.relaxation_time > 0.0)
    o.line(1, "relaxation_time", yaml_real(c.relaxation_time));
  else
    o.line(1, "beta", yaml_real(c.beta));
  o.line(1, "added_mass", yaml_real(c.added_mass));
  o.line(1, "dilatation", c.dilatation ? "true" : "false");
  o.line(1, "continuity", name_of(scene_names::kContinuity, c.continuity));
  if (c.network_inlet) {
    o.line(1, "network_inlet", vec3(*c.network_inlet));
    o.line(1, "network_inlet_extent", vec3(c.network_inlet_extent));
  }
  o.line(1, "coupling", name_of(scene_names::kWindowCoupling, c.coupling));
}

void emit_fracture_flow(Lines& o, const FractureFlowSpec& f) {
  o.line(0, "fracture_flow");
  o.line(1, "density", yaml_real(f.density));
  o.line(1, "viscosity", yaml_real(f.viscosity));
  o.line(1, "bulk_modulus", yaml_real(f.bulk_modulus));
  o.line(1, "reference_pressure", yaml_real(f.reference_pressure));
  o.line(1, "aperture_floor", yaml_real(f.aperture_floor));
  o.line(1, "lag_pressure", yaml_real(f.lag_pressure));
  o.line(1, "initial_pressure", yaml_real(f.initial_pressure));
  o.line(1, "interval", std::to_string(f.interval));
  o.line(1, "wet_damage", yaml_real(f.wet_damage));
  o.line(1, "solver", name_of(scene_names::kNetworkSolver, f.solver));
  o.line(1, "injection");
  o.line(2, "point", vec3(f.point));
  if (f.rate) emit_time_function(o, 2, "rate", *f.rate);
  if (f.pressure) emit_time_function(o, 2, "pressure", *f.pressure);
  if (!f.well_surfaces.empty()) {
    std::string wall;
    for (const auto& v : f.well_surfaces) wall += (wall.empty() ? "" : ", ") + quoted(v);
    o.line(2, "surfaces", "[" + wall + "]");
  }
  o.line(2, "well_volume", yaml_real(f.well_volume));
  o.line(2, "well_compliance", yaml_real(f.well_compliance));
  o.line(1, "vent_pressure", f.vent_pressure ? yaml_real(*f.vent_pressure) : "null");
  std::string surfaces;
  for (const auto& v : f.vent_surfaces) surfaces += (surfaces.empty() ? "" : ", ") + quoted(v);
  o.line(1, "vent_surfaces", "[" + surfaces + "]");
  o.line(1, "leak_off", yaml_real(f.leak_off));
  o.line(1, "spurt", yaml_real(f.spurt));
}

void emit_checkpoint(Lines& o, const CheckpointSpec& c) {
  o.line(0, "checkpoint");
  o.line(1, "every_steps", std::to_string(c.every_steps));
  o.line(1, "every_seconds", yaml_real(c.every_seconds));
  o.line(1, "keep", std::to_string(c.keep));
}

void emit_reference(Lines& o, const std::vector<ReferenceMetricSpec>& reference) {
  if (reference.empty()) return;
  o.line(0, "reference");
  for (const auto& m : reference) {
    o.item(1, "name", quoted(m.name));
    if (m.summary.empty()) {
      o.line(2, "series", quoted(m.series));
      o.line(2, "reduce", name_of(scene_names::kReduce, m.reduce));
    } else {
      o.line(2, "summary", quoted(m.summary));
    }
    o.line(2, "factor", yaml_real(m.factor));
    if (m.value) o.line(2, "value", yaml_real(*m.value));
  }
}

void emit_probes(Lines& o, const std::vector<ProbeSpec>& probes) {
  if (probes.empty()) return;
  o.line(0, "probes");
  for (const auto& p : probes) {
    o.item(1, "name", quoted(p.name));
    o.line(2, "field", p.field);
    o.line(2, "component", p.component);
    o.line(2, "factor", yaml_real(p.factor));
    o.line(2, "points");
    for (const auto& q : p.points) {
      o.item(3, "at", vec3(q.at));
      if (q.value) o.line(4, "value", yaml_real(*q.value));
    }
  }
}

}  // namespace

std::string emit_resolved_yaml(const Scene& scene) {
  Lines o;
  o.text() += "# Resolved scene: every key, defaults filled, overrides applied (docs/scene-format.md).\n";
  o.line(0, "scene");
  o.line(1, "name", quoted(scene.name));
  o.line(1, "description", quoted(scene.description));
  emit_time(o, scene.time);
  if (scene.mesh.file || scene.mesh.generate) emit_mesh(o, scene.mesh);
  if (scene.solid) emit_solid(o, *scene.solid);
  if (scene.fluid) emit_fluid(o, *scene.fluid);
  if (scene.fluid_solid) emit_fluid_solid(o, *scene.fluid_solid);
  if (scene.fracture_flow) emit_fracture_flow(o, *scene.fracture_flow);
  emit_output(o, scene.output);
  emit_checkpoint(o, scene.checkpoint);
  emit_reference(o, scene.reference);
  emit_probes(o, scene.probes);
  return std::move(o.text());
}

std::string fnv1a64_hex(std::string_view text) {
  return hex16(fnv1a64(text.data(), text.size()));
}

std::string scene_hash(const Scene& scene) {
  std::string text = scene.resolved_yaml;
  if (scene.mesh.file) text += "# mesh.file content fnv1a64 " + scene.mesh.file_fnv1a64 + "\n";
  if (scene.fluid && scene.fluid->mesh && scene.fluid->mesh->file)
    text += "# fluid.mesh.file content fnv1a64 " + scene.fluid->mesh->file_fnv1a64 + "\n";
  return fnv1a64_hex(text);
}

}  // namespace rift
