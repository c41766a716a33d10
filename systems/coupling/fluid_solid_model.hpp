#pragma once
// The two-way fluid-solid coupling (docs/coupling.md): the solid immersed in the fluid's own mesh as a
// volume fraction, the flow inside it relaxed to its velocity by an implicit absorption, and the fluid's
// force handed back to the solid's nodes. Exists only in a scene with both a solid and a fluid.
//
// It owns the two exchange systems, which the step script (systems/step_script.cpp) places around the
// fluid step in each window (the sequential coupling), or runs its exchanges after the graph while the
// fluid steps beside it (the concurrent coupling, as BackgroundWork); the run's step is the solid's,
// fluid.dt = substeps x that. At t = 0 it exchanges once, so the first
// window already feels the fluid (buoyancy of a fluid at rest).
//
// Outputs: solid_fraction on the fluid grid, fluid_force on the solid grid; time-series columns
// fluid_solid_*; summary metrics.fluid_solid. Health: a non-finite fluid force, or a fluid force total
// that disagrees with the fluid's absorption (Newton's third law), stops the run with a diagnosis.
#include <memory>

#include "engine/core/table.hpp"
#include "engine/model.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/step_plan.hpp"
#include "systems/coupling/concurrent_fluid_step.hpp"
#include "systems/coupling/fluid_mesh_adapter.hpp"
#include "systems/coupling/fluid_solid_exchange.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/solid_model.hpp"

namespace rift {

class FluidSolidModel : public Model, public BackgroundWork {
 public:
  // adapter: fluid.adapt (else null); the fluid is remeshed after every adapter->interval() fluid steps,
  // at the window's end, between the fluid's force on the solid and the solid's state going to the fluid.
  // well_wall_tets: with fluid_solid.network_inlet, the solid tets on the network's well (the notch):
  // with the broken joints' tets they mark the fluid cells the network owns (SolidToFluidSystem).
  FluidSolidModel(Store& store, SolidModel& solid, FluidModel& fluid, const FluidSolidSpec& spec,
                  std::unique_ptr<FluidMeshAdapter> adapter = nullptr,
                  std::vector<int32_t> well_wall_tets = {});
  ~FluidSolidModel() override;

  std::string name() const override { return "fluid_solid"; }
  void restored(const StepContext& at) override;
  std::optional<std::string> check_health(const StepContext& after) override;
  void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) override;
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;
  std::vector<SystemTiming> timings() const override;

  // What the step script places (systems/step_script.cpp). The exchange systems, run in the graph around
  // the fluid step at each window's end (sequential coupling).
  System* to_fluid() { return to_fluid_.get(); }
  System* to_solid() { return to_solid_.get(); }
  bool concurrent() const { return concurrent_ != nullptr; }
  // fluid.adapt: the fluid is remade after every this many fluid steps (0: never, or no fluid.adapt).
  int64_t remesh_interval() const { return adapter_ ? adapter_->interval() : 0; }
  // After-graph stages at a window's end, `taken` the step that ends it. The concurrent coupling's
  // exchanges: the fluid's force to the solid for the next window; the solid at the window's end to the
  // fluid for its next step. fluid.adapt: the fluid's mesh remade around the solid (the sequential
  // coupling then hands the new mesh the solid's state with exchange_solid_to_fluid).
  void exchange_fluid_to_solid(const StepContext& taken);
  void remesh_fluid(const StepContext& taken);
  void exchange_solid_to_fluid(const StepContext& taken);

  // The concurrent coupling's fluid step as work beside the graph (BackgroundWork, a `beside` stage):
  // launched at a window's start from what the exchange at t_n gave the solver, joined at its end. A
  // join mid-window (a checkpoint, the end of a stopped run) leaves the stored fluid state at the window's
  // end. access(): the fluid step's declared columns.
  void launch(const StepContext& at) override;
  void join() override;
  Access access() const override;

  // The fewest solid steps per fluid step that keep dt_s <= safety x the solid's stable step.
  static int64_t automatic_substeps(double fluid_dt, double solid_stable_dt, double safety);

 private:
  void keep_exchange_positions();  // concurrent: solid_node.x_at_exchange = x
  // fluid.adapt: the fluid's mesh remade around the solid now, and what the exchange derived from it.
  void adapt_fluid_mesh(double time);
  void fluid_mesh_changed();

  Store& store_;
  FluidModel& fluid_;
  FluidSolidSpec spec_;
  ExchangeSettings settings_;
  double solid_volume_ = 0.0;  // of the solid at t = 0
  ExchangePairs pairs_;
  std::unique_ptr<SolidToFluidSystem> to_fluid_;
  std::unique_ptr<FluidToSolidSystem> to_solid_;
  FluidStepSystem* fluid_step_ = nullptr;            // concurrent only: the fluid's step, driven from here
  std::unique_ptr<ConcurrentFluidStep> concurrent_;  // concurrent only
  SystemTiming to_solid_time_{"fluid_to_solid"}, to_fluid_time_{"solid_to_fluid"};
  std::unique_ptr<FluidMeshAdapter> adapter_;  // fluid.adapt only
  SystemTiming remesh_time_{"fluid_remesh"};
};

}  // namespace rift
