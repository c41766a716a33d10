#pragma once
// Internal forces of the tetrahedra (compressible neo-Hookean + viscous damping + in-situ stress,
// kernels/tet_forces). Reads node positions and velocities, writes each tet's corner forces, stress,
// elastic energy and viscous power, and books the damping dissipation of the step in solid_energy.
#include <vector>

#include "engine/core/table.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/tet_forces.hpp"

namespace rift {

class TetForceSystem : public System {
 public:
  // initial_stress: 6 per material (empty: none).
  TetForceSystem(Store& store, std::vector<kernels::TetMaterial> materials,
                 std::vector<double> initial_stress);
  std::string name() const override { return "tet_forces"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  // Inverted tets (J <= 0) seen in the last step, and the lowest index among them.
  size_t inverted() const { return inverted_; }
  int64_t first_inverted() const { return first_inverted_; }

 private:
  struct Block {
    kernels::TetForceStatus status;
    double viscous_power = 0.0;
  };
  Store& store_;
  std::vector<kernels::TetMaterial> materials_;
  std::vector<double> initial_stress_;
  std::vector<Block> blocks_;  // one per block, sized once
  size_t inverted_ = 0;
  int64_t first_inverted_ = -1;
};

}  // namespace rift
