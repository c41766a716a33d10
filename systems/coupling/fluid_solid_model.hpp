#pragma once
// The two-way fluid-solid coupling (docs/coupling.md): the solid immersed in the fluid's own mesh as a
// volume fraction, the flow inside it relaxed to its velocity by an implicit absorption, and the fluid's
// force handed back to the solid's nodes. Exists only in a scene with both a solid and a fluid.
//
// It owns the two exchange systems and places them around the fluid step (FluidModel::surround_step);
// the run's step is the solid's, fluid.dt = substeps x that. At t = 0 it exchanges once, so the first
// window already feels the fluid (buoyancy of a fluid at rest).
//
// Outputs: solid_fraction on the fluid grid, fluid_force on the solid grid; time-series columns
// fluid_solid_*; summary metrics.fluid_solid. Health: a non-finite fluid force, or a fluid force total
// that disagrees with the fluid's absorption (Newton's third law), stops the run with a diagnosis.
#include <memory>

#include "engine/core/table.hpp"
#include "engine/model.hpp"
#include "engine/scene/scene.hpp"
#include "systems/coupling/concurrent_fluid_step.hpp"
#include "systems/coupling/fluid_mesh_adapter.hpp"
#include "systems/coupling/fluid_solid_exchange.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/solid_model.hpp"

namespace rift {

class FluidSolidModel : public Model {
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
  std::vector<System*> systems() override { return {}; }  // placed by the fluid model
  void restored(const StepContext& at) override;
  std::optional<std::string> check_health(const StepContext& after) override;
  void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) override;
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;
  // fluid_solid.coupling: concurrent (docs/coupling.md): the fluid step as a task from the start of each
  // window, joined at its end; the exchanges run between the two, outside the step graph.
  void before_step(const StepContext& at) override;
  void after_step(const StepContext& taken) override;
  void join() override;
  Access background_access() const override;
  std::vector<SystemTiming> timings() const override;

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
