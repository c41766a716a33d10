#pragma once
// Pressure, traction and in-situ stress on named surfaces, with time functions from the scene, and the
// crack pressure on the faces of broken joints (solid.fracture.crack_pressure). Writes each loaded face's
// corner forces; the node pass gathers them.
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
  // crack_face_begin: faces from this row on are joint faces, 2 per joint in joint order (SolidModel::
  // add_crack_faces); only those of broken joints are pressed. The face table's size when there are none.
  SurfaceLoadSystem(Store& store, std::vector<SolidBoundarySpec> loads, std::array<double, 6> initial_stress,
                    size_t crack_face_begin);
  std::string name() const override { return "surface_loads"; }
  Access access() const override;
  void run(const StepContext& ctx) override;
  size_t pressed_crack_faces() const;

 private:
  Store& store_;
  std::vector<SolidBoundarySpec> specs_;
  std::array<double, 6> initial_stress_;
  std::vector<kernels::FaceLoad> values_;  // evaluated each step, sized once
  size_t crack_face_begin_;
  bool has_crack_faces_;
};

}  // namespace rift
