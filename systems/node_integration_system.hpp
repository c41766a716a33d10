#pragma once
// The node pass: gathers every producer's corner forces, then advances velocities and positions
// by central difference, holding constrained components at their prescribed velocity, and books the
// work of internal and external forces over the step in the solid_energy table. With contact, the
// per-node contact forces (solid_node.contact_force) join the internal forces, the pressed crack faces'
// (solid_node.crack_force) the external ones.
#include <vector>

#include "engine/core/table.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/node_integration.hpp"

namespace rift {

class NodeIntegrationSystem : public System {
 public:
  // velocity_conditions[i] drives nodes whose `held` column is i (fixed supports are velocity 0).
  // mass_damping: solid.mass_damping [1/s], evaluated at the start of each step (0: none).
  NodeIntegrationSystem(Store& store, std::vector<SolidBoundarySpec> velocity_conditions,
                        std::array<double, 3> gravity, TimeFunction mass_damping = {});
  std::string name() const override { return "node_integration"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  size_t non_finite_nodes() const { return non_finite_; }
  // Also gather the per-node external forces of solid_node.<column> (3 per node; the fluid's), booked as
  // external work. Before the step graph is built.
  void add_external_node_force(std::string column) { external_column_ = std::move(column); }

 private:
  Store& store_;
  std::vector<SolidBoundarySpec> conditions_;
  std::array<double, 3> gravity_;
  TimeFunction mass_damping_;
  bool damped_ = false;             // the damping is positive at some time: its dissipation is booked
  std::vector<double> prescribed_;  // 3 per condition, evaluated each step
  std::vector<kernels::NodeStepResult> blocks_;
  size_t non_finite_ = 0;
  std::string external_column_;  // empty: none
  bool contact_ = false;         // solid_node.contact_force exists (a contact system gathers into it)
  bool crack_ = false;  // solid_node.crack_force exists (the surface loads gather crack faces into it)
};

}  // namespace rift
