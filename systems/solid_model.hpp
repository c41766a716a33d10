#pragma once
// The solid: builds its tables from a mesh and the scene's solid section, and owns the systems that
// advance it (surface loads, tet forces, node integration). This first version keeps the mesh
// continuous (tets share nodes); the fracture zone with per-tet nodes and joints builds on it.
#include <memory>

#include "engine/core/table.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/model.hpp"
#include "engine/scene/scene.hpp"
#include "systems/node_integration_system.hpp"
#include "systems/surface_load_system.hpp"
#include "systems/tet_force_system.hpp"

namespace rift {

class SolidModel : public Model {
 public:
  // Throws rift::Error naming the scene key when the scene and the mesh disagree (unknown surface or
  // region, tets without a material, an inverted tet in the input).
  SolidModel(Store& store, const TetMesh& mesh, const SolidSpec& spec);

  std::string name() const override { return "solid"; }
  std::vector<System*> systems() override;
  double stable_dt() const override { return stable_dt_; }
  std::optional<std::string> check_health(const StepContext& after) override;
  void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) override;
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;

 private:
  void build_nodes_and_tets(const TetMesh& mesh);
  void assign_materials(const TetMesh& mesh);
  void apply_boundaries(const TetMesh& mesh);
  void build_force_slots();
  void compute_mass_and_stable_dt();

  Store& store_;
  SolidSpec spec_;
  std::vector<kernels::TetMaterial> tet_materials_;
  std::vector<SolidBoundarySpec> velocity_conditions_, load_conditions_;
  double stable_dt_ = 0.0;
  int64_t critical_tet_ = -1;
  std::unique_ptr<SurfaceLoadSystem> loads_;
  std::unique_ptr<TetForceSystem> tet_forces_;
  std::unique_ptr<NodeIntegrationSystem> integration_;
  // Output scratch, reused between outputs.
  std::vector<double> displacement_, principal_;
  std::vector<int32_t> region_;
};

}  // namespace rift
