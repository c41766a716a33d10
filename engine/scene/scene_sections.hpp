#pragma once
// Readers of the top-level sections of a scene file, one function each, so a new section (fluid,
// contact, ...) is one more function here and one more line in read_scene_tree (load_scene.cpp).
// Each reads every key of its section through `sec` and calls sec.finish().
#include <string>

#include "engine/scene/scene.hpp"
#include "engine/scene/yaml_reader.hpp"

namespace rift {

void read_scene_section(MapReader& sec, Scene& scene);  // name, description
TimeSpec read_time_section(MapReader& sec);
// Relative mesh.file paths are resolved against `base_dir` (the scene file's folder).
MeshSpec read_mesh_section(MapReader& sec, const std::string& base_dir);
SolidSpec read_solid_section(MapReader& sec);
// fluid.mesh paths resolve against base_dir like mesh.file (read_fluid_section.cpp).
FluidSpec read_fluid_section(MapReader& sec, const std::string& base_dir);
// Parts of the solid section (read_fracture_keys.cpp).
FractureMaterialSpec read_fracture_material(MapReader& sec, double young);
FractureSpec read_fracture_section(MapReader& sec);
InitialStressSpec read_initial_stress_section(MapReader& sec);
ContactSpec read_contact_section(MapReader& sec);
FluidSolidSpec read_fluid_solid_section(MapReader& sec);  // read_fluid_section.cpp
// pressure_from_fluid: fluid_solid.network_inlet is given, and the well takes neither rate nor pressure.
FractureFlowSpec read_fracture_flow_section(MapReader& sec, bool pressure_from_fluid);
OutputSpec read_output_section(MapReader& sec);
CheckpointSpec read_checkpoint_section(MapReader& sec);
ReferenceMetricSpec read_reference_metric(MapReader& sec);
// One item of `probes` (read_probes_section.cpp); its field must belong to a model the scene has.
ProbeSpec read_probe(MapReader& sec, bool has_solid, bool has_fluid);

}  // namespace rift
