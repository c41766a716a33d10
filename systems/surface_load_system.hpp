#pragma once
// Pressure and traction on named surfaces, with time functions from the scene. Writes each loaded
// face's corner forces; the node pass gathers them.
#include <vector>

#include "engine/core/table.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/surface_load.hpp"

namespace rift {

class SurfaceLoadSystem : public System {
 public:
  // loads[i] is the scene's boundary condition behind load index i of solid_load_face.load.
  SurfaceLoadSystem(Store& store, std::vector<SolidBoundarySpec> loads);
  std::string name() const override { return "surface_loads"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

 private:
  Store& store_;
  std::vector<SolidBoundarySpec> specs_;
  std::vector<kernels::FaceLoad> values_;  // evaluated each step, sized once
};

}  // namespace rift
