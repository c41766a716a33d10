#pragma once
// The fluid in the cracks (scene section fracture_flow; docs/hydraulic-fracture.md): owns the network
// flow system, reports its diagnosis, its metrics (well pressure, injected, crack and fluid volumes,
// extents, efficiency, the mass and energy books) and the crack network as an output grid.
#include <memory>

#include "engine/mesh/tet_mesh.hpp"
#include "engine/model.hpp"
#include "systems/fracture_flow/fracture_flow_system.hpp"

namespace rift {

class SolidModel;

class FractureFlowModel : public Model {
 public:
  // Before the step graph is built: makes the solid read solid_node.crack_force.
  FractureFlowModel(Store& store, SolidModel& solid, const TetMesh& mesh, const FractureFlowSpec& spec);
  std::string name() const override { return "fracture_flow"; }
  System* system() { return system_.get(); }  // the network's step (systems/step_script.cpp places it)
  void restored(const StepContext& at) override { system_->restored(); }
  std::optional<std::string> check_health(const StepContext& after) override;
  void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) override;
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;
  // The solid tets with a face on the well's wall (the notch, fracture_flow.injection.surfaces), sorted.
  std::vector<int32_t> well_wall_tets() const;

 private:
  Store& store_;
  FractureFlowSpec spec_;
  std::unique_ptr<FractureFlowSystem> system_;
  // Output buffers (the grid's arrays live until the series has written them).
  std::vector<double> points_, point_pressure_, point_aperture_, point_wetting_;
  std::vector<int32_t> triangles_, rows_;
};

}  // namespace rift
