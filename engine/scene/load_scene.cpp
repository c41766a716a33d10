#include "engine/scene/load_scene.hpp"

#include <algorithm>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/io/input_file.hpp"
#include "engine/scene/resolved_yaml.hpp"
#include "engine/scene/scene_overrides.hpp"
#include "engine/scene/scene_sections.hpp"
#include "engine/scene/yaml_reader.hpp"

namespace rift {
namespace {

// `root[section][key]` exists (before the section is read, to decide what is required).
bool has_mapping_key(const YamlNode& root, std::string_view section, std::string_view key) {
  if (root.kind != YamlNode::Kind::mapping) return false;
  for (const auto& e : root.entries)
    if (e.key == section && e.value.kind == YamlNode::Kind::mapping)
      for (const auto& k : e.value.entries)
        if (k.key == key) return true;
  return false;
}

// The whole document, section by section in schema order. A new top-level section is one more line.
Scene read_scene_tree(ReadContext& ctx, const YamlNode& root, const std::string& file_label,
                      const std::string& base_dir) {
  Scene scene;
  const SourceLocation top{file_label, 1, 1};
  if (root.kind != YamlNode::Kind::mapping && root.kind != YamlNode::Kind::null) {
    ctx.error(root.where, "", "a mapping of sections (scene, time, mesh, ...)", describe_found(root));
    return scene;
  }
  MapReader doc(ctx, root.kind == YamlNode::Kind::mapping ? &root : nullptr, "", "", top);
  doc.record_values_at_root();
  MapReader scene_sec = doc.section("scene", true);
  read_scene_section(scene_sec, scene);
  MapReader time = doc.section("time", true);
  scene.time = read_time_section(time);
  // A fluid scene with its own fluid.mesh needs no top-level mesh.
  const bool fluid_mesh = has_mapping_key(root, "fluid", "mesh");
  const bool has_mesh = doc.has("mesh");
  MapReader mesh = doc.section("mesh", !fluid_mesh);
  if (has_mesh || !fluid_mesh) scene.mesh = read_mesh_section(mesh, base_dir);
  const bool has_solid = doc.has("solid");
  MapReader solid = doc.section("solid", false);
  if (has_solid) scene.solid = read_solid_section(solid);
  const bool has_fluid = doc.has("fluid");
  MapReader fluid = doc.section("fluid", false);
  if (has_fluid) {
    scene.fluid = read_fluid_section(fluid, base_dir);
    if (has_solid && !fluid_mesh)
      doc.error("fluid",
                "a fluid.mesh when the scene also has a solid (the fluid's own mesh, covering the solid)",
                "no fluid.mesh; the top-level mesh is the solid's");
    else if (!has_solid && scene.fluid->adapt)
      doc.error("fluid",
                "fluid.adapt only in a scene with a solid (the mesh is refined at the solid's surface)",
                "fluid.adapt without a solid section");
    else if (!has_solid && fluid_mesh && has_mesh)
      doc.error("mesh", "no top-level mesh when fluid.mesh is given (nothing else would use it)",
                "keep one of mesh and fluid.mesh");
  }
  if (has_solid && !has_fluid)
    for (const auto& bc : scene.solid->boundaries)
      if (bc.kind == SolidBoundarySpec::Kind::fluid_pressure) {
        doc.error(
            "solid", "no boundary of type fluid_pressure in a scene without a fluid section",
            "surface '" + bc.surface + "' is fluid_pressure; add a fluid section or use type: pressure");
        break;
      }
  const bool has_coupling = doc.has("fluid_solid");
  MapReader coupling = doc.section("fluid_solid", false);
  if (has_solid && has_fluid) {
    scene.fluid_solid = read_fluid_solid_section(coupling);
    bool wetted = false;
    for (const auto& bc : scene.solid->boundaries)
      wetted = wetted || bc.kind == SolidBoundarySpec::Kind::fluid_pressure;
    const bool by_faces = scene.fluid_solid->force == FluidSolidSpec::Force::wetted_faces;
    // With a network inlet the fluid reaches the rock through the cracks' network: wetted faces need not
    // be named.
    const bool through_network = scene.fluid_solid->network_inlet.has_value();
    if (wetted != by_faces && !(by_faces && through_network))
      doc.error(
          has_coupling ? "fluid_solid" : "solid",
          by_faces ? "fluid_solid.force: wetted_faces with at least one solid boundary of type fluid_pressure"
                   : "fluid_solid.force: wetted_faces when a solid boundary is of type fluid_pressure",
          by_faces ? "no fluid_pressure boundary, so nothing would feel the fluid"
                   : "the volume force already includes the fluid's pressure; with wetted faces as well it "
                     "would count twice");
  } else if (has_coupling)
    doc.error("fluid_solid", "a fluid_solid section only in a scene with both a solid and a fluid section",
              std::string("a scene with ") +
                  (has_solid   ? "a solid"
                   : has_fluid ? "a fluid"
                               : "neither") +
                  " only");
  const bool has_fracture_flow = doc.has("fracture_flow");
  MapReader fracture_flow = doc.section("fracture_flow", false);
  if (has_fracture_flow) {
    scene.fracture_flow = read_fracture_flow_section(
        fracture_flow, scene.fluid_solid && scene.fluid_solid->network_inlet.has_value());
    if (!has_solid || !scene.solid->fracture)
      doc.error("fracture_flow",
                "a fracture_flow section only with a solid.fracture section (the cracks it fills)",
                "no fracture zone in the scene");
    else if (scene.solid->fracture->crack_pressure)
      doc.error("fracture_flow",
                "either fracture_flow or solid.fracture.crack_pressure: the prescribed crack pressure is the "
                "limit of this flow (no viscosity, no compressibility), and both would press the cracks",
                "both are given; remove solid.fracture.crack_pressure");
  }
  if (scene.fluid_solid && scene.fluid_solid->network_inlet && !has_fracture_flow)
    doc.error("fluid_solid",
              "fluid_solid.network_inlet only with a fracture_flow section (the network it feeds)",
              "no fracture_flow section");
  else if (scene.fluid_solid && scene.fluid_solid->network_inlet &&
           scene.fluid_solid->coupling == FluidSolidSpec::Coupling::concurrent)
    doc.error("fluid_solid", "fluid_solid.network_inlet with coupling: sequential",
              "coupling: concurrent (its fluid step would take the network's sink a window late)");
  MapReader output = doc.section("output", false);
  scene.output = read_output_section(output);
  MapReader checkpoint = doc.section("checkpoint", false);
  scene.checkpoint = read_checkpoint_section(checkpoint);
  for (MapReader& m : doc.section_list("reference", 0)) scene.reference.push_back(read_reference_metric(m));
  for (MapReader& m : doc.section_list("probes", 0)) {
    scene.probes.push_back(read_probe(m, has_solid, has_fluid));
    const std::string& name = scene.probes.back().name;
    if (std::count_if(scene.probes.begin(), scene.probes.end(),
                      [&](const ProbeSpec& q) { return q.name == name; }) > 1)
      m.error("name", "a name no other probe has", "'" + name + "' is taken");
  }
  doc.finish();
  return scene;
}

}  // namespace

SceneLoadResult read_scene_text(const std::string& yaml, const std::string& file_label,
                                const std::string& base_dir, const std::vector<std::string>& overrides,
                                SchemaRecorder* recorder) {
  SceneLoadResult result;
  YamlParseResult parsed = parse_yaml_tree(yaml, file_label);
  if (parsed.error) {
    result.errors.push_back(*parsed.error);
    return result;
  }
  ReadContext ctx(recorder);
  apply_overrides(parsed.root, overrides, ctx);
  Scene scene = read_scene_tree(ctx, parsed.root, file_label, base_dir);
  result.errors = ctx.errors();
  // Overrides first (they have no line), then the file top to bottom, whatever order checks ran in.
  std::stable_sort(result.errors.begin(), result.errors.end(), [](const auto& a, const auto& b) {
    return std::pair(a.line, a.column) < std::pair(b.line, b.column);
  });
  result.consumed_keys.assign(ctx.consumed_keys().begin(), ctx.consumed_keys().end());
  if (!result.errors.empty()) return result;
  scene.source_file = file_label;
  scene.resolved_yaml = emit_resolved_yaml(ctx.resolved());
  scene.hash = scene_hash(scene);
  result.scene = std::move(scene);
  return result;
}

SceneLoadResult read_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  std::string text;
  try {
    text = read_input_file(path, InputFileLimit{scene_file_max_bytes, ""}, "scene file");
  } catch (const Error& e) {
    // The message starts with the path, which the diagnostic names already.
    std::string found = e.what();
    if (found.rfind(path + ": ", 0) == 0) found.erase(0, path.size() + 2);
    SceneLoadResult result;
    result.errors.push_back({path, 0, 0, "", "a readable scene file", found, ""});
    return result;
  }
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  return read_scene_text(text, path, base_dir, overrides);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  SceneLoadResult result = read_scene_file(path, overrides);
  if (result.errors.empty()) return std::move(*result.scene);
  std::string message;
  for (const auto& e : result.errors) message += (message.empty() ? "" : "\n") + e.format();
  throw Error(message);
}

}  // namespace rift
