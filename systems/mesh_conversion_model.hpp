#pragma once
// The continuous meshes of the solid for whoever consumes them: the fluid coupling, or an output that
// asks for the surface (output.surface). Exists in a run only with such a consumer (model only what the
// scene requires). Writes the surface mesh as the grid "surface" (triangles on the continuous vertices,
// tagged boundary / notch / fracture, each fracture triangle with the time its joint broke), and puts
// the number of vertices, surface triangles, fracture surfaces and solid fragments in the time series
// and the summary.
#include <memory>
#include <string>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/mesh/mesh_conversion.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/model.hpp"
#include "systems/mesh_conversion_system.hpp"

namespace rift {

class MeshConversionModel : public Model {
 public:
  // Needs the solid's tables in `store`. External faces on the mesh surfaces named in notch_surfaces
  // are tagged notch (pre-existing), the other external faces boundary.
  MeshConversionModel(Store& store, const TetMesh& mesh, const std::vector<std::string>& notch_surfaces);

  std::string name() const override { return "mesh_conversion"; }
  // Follows the fractures as joints break (null without joints); systems/step_script.cpp places it.
  System* system() { return system_.get(); }
  void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) override;
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;

  // Up to date with every break so far (for consumers outside the step graph: output, tests).
  const MeshConversion& conversion();
  // As the last step left it, without catching up (what a consumer inside the step graph sees).
  const MeshConversion& state() const { return *conversion_; }
  // Vertex positions and velocities from the solid's nodes now.
  void update_kinematics();

 private:
  Store& store_;
  std::vector<std::array<int32_t, 3>> notch_triangles_;
  std::unique_ptr<MeshConversion> conversion_;
  std::unique_ptr<MeshConversionSystem> system_;
  std::vector<uint8_t> tag_;  // output scratch
};

}  // namespace rift
