#pragma once
// Keeps the continuous volume and surface meshes (engine/mesh/mesh_conversion.hpp) in step with the
// fracture: runs after the joint forces, in the same step, and folds every joint that broke into the
// surface before the step ends, so a consumer never sees the fracture late (the lag of Guo et al.'s
// conversion). Its input is the fracture log (solid_fracture_event), read from the first row it has not
// seen: O(new breaks) per step, nothing at all in a step without one. A restarted run starts with an
// empty conversion and replays the restored log in its order, which rebuilds the same numbering.
#include <memory>

#include "engine/core/table.hpp"
#include "engine/mesh/mesh_conversion.hpp"
#include "engine/schedule/system.hpp"

namespace rift {

class MeshConversionSystem : public System {
 public:
  MeshConversionSystem(Store& store, MeshConversion& conversion);
  std::string name() const override { return "mesh_conversion"; }
  Access access() const override;
  void run(const StepContext& ctx) override { catch_up(); }

  // Folds in the fracture log's rows not yet seen (also called before an output).
  void catch_up();

 private:
  Store& store_;
  MeshConversion& conversion_;
  size_t events_seen_ = 0;
};

}  // namespace rift
