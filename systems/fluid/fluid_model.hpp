#pragma once
// The fluid in a run: a FluidSolver (incompressible Navier-Stokes, docs/fluid.md) on its own mesh, built
// from the scene's fluid section, stepped by FluidStepSystem with the fixed step fluid.dt. Its state lives
// in the fluid tables (fluid_tables.hpp), whose columns the solver works on, so outputs, the state hash
// and checkpoints cover it; restored() has the solver take up a checkpoint's values so a restart continues
// bit for bit.
//
// Outputs: the grid "fluid" (velocity, pressure per node; divergence, cfl per cell), time-series columns
// fluid_*, summary metrics.fluid. Health: non-finite velocity or pressure, or (on_picard_failure: stop) a
// step whose Picard iteration did not converge, stops the run with a diagnosis.
#include <memory>

#include "engine/core/table.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/model.hpp"
#include "engine/scene/scene.hpp"
#include "systems/fluid/fluid_solver.hpp"
#include "systems/fluid/fluid_step_system.hpp"

namespace rift {

class FluidModel : public Model {
 public:
  // Throws rift::Error naming the scene key when the scene and the mesh disagree (unknown surface, a
  // free-slip surface that is not an axis-aligned plane, ...).
  // With a solid: the fluid steps once every `substeps` run steps (FluidStepSystem), after the coupling
  // wrote `coupling_reads`.
  FluidModel(Store& store, const TetMesh& mesh, const FluidSpec& spec, int64_t substeps = 1,
             std::vector<std::string> coupling_reads = {});
  ~FluidModel() override;

  std::string name() const override { return "fluid"; }
  // The fluid's step (once per window of substeps() run steps): a system of the step graph, or, with the
  // concurrent coupling, work beside it (systems/coupling/concurrent_fluid_step.hpp). The step script
  // (systems/step_script.cpp) places it.
  FluidStepSystem& step() { return *step_; }
  std::optional<double> required_dt() const override { return spec_.dt / static_cast<double>(substeps_); }
  std::optional<std::string> check_health(const StepContext& after) override;
  void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) override;
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;
  void partition_work(std::vector<PartitionWork>& domains) const override;
  void restored(const StepContext& at) override;

  // fluid.adapt: `mesh` (same box and surfaces) replaces the fluid's mesh at `time`; velocity, pressure and
  // the previous velocity are interpolated (P1) onto it. The solver object stays (references to it hold);
  // its spans (nodes, tets, volumes, ...) change. The coupling refreshes what it derived from the mesh.
  void remesh(const TetMesh& mesh, double time);
  // How many times the mesh was remade (0 without fluid.adapt).
  int64_t mesh_revision() const;

  const fluid::FluidSolver& solver() const { return *solver_; }
  fluid::FluidSolver& solver() { return *solver_; }
  const FluidSpec& spec() const { return spec_; }
  int64_t substeps() const { return substeps_; }
  // 1/2 rho sum_n V_n |u_n|^2 (lumped) [J], of the stored velocity (what the run loop may read: with the
  // concurrent coupling the solver's own may be mid-step).
  double kinetic_energy() const;

 private:
  void cell_fields();                      // divergence_ and cfl_ from the current velocity
  void build_solver(const TetMesh& mesh);  // a new solver on `mesh` (in place of the old one, if any)
  void use_store_state();                  // the fluid tables' state columns become the solver's
  void store_mesh(const TetMesh& mesh);    // the fluid tables' rows, mesh columns and boundary faces
  TetMesh mesh_from_store() const;         // fluid.adapt: the mesh the store holds

  Store& store_;
  FluidSpec spec_;
  int64_t substeps_;
  std::unique_ptr<fluid::FluidSolver> solver_;
  std::unique_ptr<FluidStepSystem> step_;
  std::vector<std::string> surface_names_;  // the mesh's (a remesh keeps them)
  std::vector<double> divergence_, cfl_;    // output scratch
};

}  // namespace rift
