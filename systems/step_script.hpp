#pragma once
// The step of a run, as a script: for the models a scene has, the ordered stages one step goes through
// (engine/schedule/step_plan.hpp). The step graph runs at the same time what the declared access of the
// systems allows and keeps this order for the rest; `rift graph` prints the script above the graph.
#include "engine/schedule/step_plan.hpp"

namespace rift {

class SolidModel;
class FractureFlowModel;
class MeshConversionModel;
class FluidModel;
class FluidSolidModel;

// The models of a run (null: not in the scene).
struct StepModels {
  SolidModel* solid = nullptr;
  FractureFlowModel* fracture_flow = nullptr;
  MeshConversionModel* conversion = nullptr;
  FluidModel* fluid = nullptr;
  FluidSolidModel* coupling = nullptr;  // with both a solid and a fluid
};

StepPlan script_step(const StepModels& models);

}  // namespace rift
