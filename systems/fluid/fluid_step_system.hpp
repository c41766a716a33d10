#pragma once
// One fluid step: advances the FluidSolver from t to t + dt on its state, which lives in the fluid tables
// (FluidModel gives the solver their columns), commits it there, and writes the step's report into the
// step table, so outputs, the state hash and checkpoints see the fluid like any other state.
#include "engine/core/table.hpp"
#include "engine/schedule/system.hpp"
#include "systems/fluid/fluid_solver.hpp"

namespace rift {

// With a solid (systems/coupling) the run's step is the solid's and the fluid steps once every `every`
// of them, on the last: from t = (step + 1 - every) dt to the end of that step. `coupling_reads` are the
// columns the coupling writes before the fluid steps (ordering only; the solver holds the values).
class FluidStepSystem : public System {
 public:
  FluidStepSystem(Store& store, fluid::FluidSolver& solver, int64_t every = 1,
                  std::vector<std::string> coupling_reads = {})
      : store_(store), solver_(solver), every_(every), coupling_reads_(std::move(coupling_reads)) {}
  std::string name() const override { return "fluid_step"; }
  Access access() const override;
  void run(const StepContext& ctx) override;  // on the last step of each window: advance, then commit

  // The two halves of run, for the concurrent coupling (systems/coupling/concurrent_fluid_step.hpp), which
  // advances in a task beside the solid's sub-steps and commits after joining it. advance reads the
  // committed state and writes the solver's spares, the preconditioner's coefficients and the pressure
  // subscale (columns nothing else reads); commit swaps the spares into velocity and pressure (no copy)
  // and writes the step's report.
  void advance(double start_time);
  void commit();
  // After a restart whose fluid step was already taken: the report of that step, from the store.
  void restore_report();

  const fluid::FluidStepReport& last_report() const { return last_; }

 private:
  Store& store_;
  fluid::FluidSolver& solver_;
  fluid::FluidStepReport last_;
  int64_t every_;
  std::vector<std::string> coupling_reads_;
};

}  // namespace rift
