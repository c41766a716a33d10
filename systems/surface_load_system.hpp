#pragma once
// Pressure, traction and in-situ stress on named surfaces, with time functions from the scene. Writes
// each loaded face's corner forces; the node pass gathers them.
#include <array>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/surface_load.hpp"

namespace rift {

class SurfaceLoadSystem : public System {
 public:
  // loads[i] is the scene's boundary condition behind load index i of solid_load_face.load.
  // initial_stress: the tensor an in_situ boundary applies (zero when the scene has none).
  SurfaceLoadSystem(Store& store, std::vector<SolidBoundarySpec> loads, std::array<double, 6> initial_stress);
  std::string name() const override { return "surface_loads"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

 private:
  Store& store_;
  std::vector<SolidBoundarySpec> specs_;
  std::array<double, 6> initial_stress_;
  std::vector<kernels::FaceLoad> values_;  // evaluated each step, sized once
};

}  // namespace rift
