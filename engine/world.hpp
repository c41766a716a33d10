#pragma once
// Everything a run simulates, built from a scene: the mesh, the store of tables, and one model per
// physics section present in the scene (model only what the scene requires). The engine holds and runs
// it; which models a scene needs, and the step they take, is the composition root's
// (systems/world_builder.hpp, systems/step_script.hpp).
#include <functional>
#include <memory>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/mesh/mesh_quality.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/model.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/step_plan.hpp"

namespace rift {

struct World {
  TetMesh mesh;
  std::unique_ptr<TetMesh> fluid_mesh;  // with a solid and a fluid: the fluid's own mesh (fluid.mesh)
  MeshQuality mesh_quality;
  double mesh_seconds = 0.0;  // wall time to read or generate the mesh
  Store store;
  std::vector<std::unique_ptr<Model>> models;
  StepPlan plan;  // the step as a script of stages over the models' systems (systems/step_script.cpp)

  std::vector<System*> systems() const { return plan.graph_systems(); }  // the graph's, in script order
  double stable_dt() const;                                              // the smallest of the models' limits
};

// Reads or generates the mesh and builds the models; throws rift::Error with a complete message.
using WorldBuilder = std::function<std::unique_ptr<World>(const Scene& scene)>;

// `section` names the spec's scene section in messages ("mesh", "fluid.mesh").
TetMesh load_mesh(const MeshSpec& spec, const std::string& section = "mesh");

}  // namespace rift
