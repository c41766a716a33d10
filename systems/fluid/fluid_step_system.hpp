#pragma once
// One fluid step: advances the FluidSolver from t to t + dt and copies its state (velocity, pressure,
// pressure-matrix coefficients) and step report into the fluid tables, so outputs, the state hash and
// checkpoints see the fluid like any other state.
#include "engine/core/table.hpp"
#include "engine/schedule/system.hpp"
#include "systems/fluid/fluid_solver.hpp"

namespace rift {

class FluidStepSystem : public System {
 public:
  FluidStepSystem(Store& store, fluid::FluidSolver& solver) : store_(store), solver_(solver) {}
  std::string name() const override { return "fluid_step"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  const fluid::FluidStepReport& last_report() const { return last_; }

 private:
  Store& store_;
  fluid::FluidSolver& solver_;
  fluid::FluidStepReport last_;
};

}  // namespace rift
