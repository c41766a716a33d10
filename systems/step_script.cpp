#include "systems/step_script.hpp"

#include "systems/coupling/fluid_solid_model.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/fracture_flow/fracture_flow_model.hpp"
#include "systems/mesh_conversion_model.hpp"
#include "systems/solid_model.hpp"

namespace rift {

namespace {

// A window of fluid.dt = n solid steps ends with the fluid's step and the two exchanges (docs/coupling.md).
void script_fluid_window(StepPlan& step, FluidModel& fluid, FluidSolidModel& coupling) {
  const int64_t n = fluid.substeps();
  const int64_t remesh = n * coupling.remesh_interval();  // 0: the fluid's mesh stays
  auto stage = [&coupling](void (FluidSolidModel::*member)(const StepContext&)) {
    return [&coupling, member](const StepContext& taken) { (coupling.*member)(taken); };
  };
  if (!coupling.concurrent()) {
    // Sequential: at the window's end the fluid sees the solid there, steps to it, and its force is
    // held on the solid's nodes over the next window.
    step.graph("fluid window: the solid to the fluid, the fluid's step, the fluid's force to the solid",
               {coupling.to_fluid(), &fluid.step(), coupling.to_solid()}, n);
    if (remesh > 0) {
      step.after("the fluid's mesh remade around the solid", remesh, stage(&FluidSolidModel::remesh_fluid));
      step.after("the solid to the new fluid mesh", remesh, stage(&FluidSolidModel::exchange_solid_to_fluid));
    }
    return;
  }
  // Concurrent: the fluid steps t_n -> t_n+1 beside the window's solid steps, from the solid at t_n;
  // joined at the window's end, then the exchanges.
  step.beside("the fluid's step, beside the window's solid steps", coupling, n);
  step.after("the fluid's force to the solid", n, stage(&FluidSolidModel::exchange_fluid_to_solid));
  if (remesh > 0)
    step.after("the fluid's mesh remade around the solid", remesh, stage(&FluidSolidModel::remesh_fluid));
  step.after("the solid to the fluid", n, stage(&FluidSolidModel::exchange_solid_to_fluid));
}

}  // namespace

StepPlan script_step(const StepModels& m) {
  StepPlan step;
  if (SolidModel* solid = m.solid) {
    // Every source of force writes its own rows (corner forces per element, one contact force per node),
    // from the positions at the step's start: they run at the same time.
    step.graph("forces on the solid: surface loads, tets, joints (and fracture), contact",
               {solid->surface_loads(), solid->tet_forces(), solid->joint_forces(), solid->contact()});
    // One pass over the nodes gathers every force in a fixed order and integrates (central difference);
    // with solid.fused_tet_pass it also computes the forces of the tets that own their nodes.
    step.graph("the node pass: gather the forces, integrate", {solid->node_integration()});
  }
  if (m.fracture_flow)  // the crack network's flow on the new openings; its pressure loads the next step
    step.graph("fluid in the cracks", {m.fracture_flow->system()});
  if (m.conversion)  // the continuous meshes follow the joints that broke in this step
    step.graph("the continuous meshes follow the fractures", {m.conversion->system()});
  if (m.coupling)
    script_fluid_window(step, *m.fluid, *m.coupling);
  else if (m.fluid)
    step.graph("the fluid's step", {&m.fluid->step()});
  return step;
}

}  // namespace rift
