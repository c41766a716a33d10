#include "systems/world_builder.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/mesh/spatial_order.hpp"
#include "systems/coupling/fluid_solid_model.hpp"
#include "systems/coupling/fluid_solid_tables.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/fracture_flow/fracture_flow_model.hpp"
#include "systems/mesh_conversion_model.hpp"
#include "systems/probe_model.hpp"
#include "systems/solid_model.hpp"
#include "systems/step_script.hpp"

namespace rift {

namespace {

// Surfaces that existed before any fracture and are not the outer boundary: the generator's notches, or a
// mesh file's physical surfaces whose name starts with "notch".
std::vector<std::string> notch_surfaces(const MeshSpec& spec, const TetMesh& mesh) {
  std::vector<std::string> names;
  if (spec.generate)
    for (const auto& n : spec.generate->notches) names.push_back(n.name);
  else
    for (const auto& s : mesh.surface_names)
      if (s.rfind("notch", 0) == 0) names.push_back(s);
  return names;
}

// A fluid on its own mesh around the solid (scene.fluid->mesh, required with a solid), and the coupling.
// The run's step is the solid's: fluid.dt / substeps.
// conversion: the solid's continuous meshes (non-null with fluid.adapt, whose mesh follows its surface).
// Fills models.fluid and models.coupling.
void add_coupled_fluid(World& world, const Scene& scene, StepModels& models) {
  MeshConversionModel* conversion = models.conversion;
  const FluidSpec& fluid = *scene.fluid;
  const FluidSolidSpec& spec = *scene.fluid_solid;
  SolidModel& solid = *models.solid;
  const double stable = solid.stable_dt();
  const int64_t automatic = FluidSolidModel::automatic_substeps(fluid.dt, stable, scene.time.safety);
  const int64_t substeps = spec.substeps > 0 ? spec.substeps : automatic;
  if (spec.substeps > 0 && fluid.dt / static_cast<double>(substeps) > stable && !scene.time.allow_unstable_dt)
    throw Error(fmt::format(
        "fluid_solid.substeps = {} makes the solid step fluid.dt / substeps = {:.6g} s, above the solid's "
        "stable step {:.6g} s. Use fluid_solid.substeps >= {} ({} at time.safety = {}), or 0 to choose it, "
        "or set time.allow_unstable_dt: true to run it on purpose.",
        substeps, fluid.dt / static_cast<double>(substeps), stable,
        static_cast<int64_t>(std::ceil(fluid.dt / stable)), automatic, scene.time.safety));
  const double windows = scene.time.end / fluid.dt;
  if (std::abs(windows - std::round(windows)) > 1e-6 * windows)
    throw Error(
        fmt::format("time.end = {:.6g} s is not a whole number of fluid steps of {:.6g} s (fluid.dt): "
                    "{:.6g}. Make time.end a multiple of fluid.dt, e.g. {:.6g} s.",
                    scene.time.end, fluid.dt, windows, std::ceil(windows) * fluid.dt));
  spdlog::info("fluid-solid coupling: {} solid steps of {:.6g} s per fluid step of {:.6g} s{}", substeps,
               fluid.dt / static_cast<double>(substeps), fluid.dt, spec.substeps > 0 ? "" : " (automatic)");
  std::unique_ptr<FluidMeshAdapter> adapter;
  if (fluid.adapt) {  // the mesh around the solid as it is at t = 0, remade as it deforms and breaks
    adapter =
        std::make_unique<FluidMeshAdapter>(world.store, *conversion, *fluid.mesh->generate, *fluid.adapt);
    world.fluid_mesh = std::make_unique<TetMesh>(adapter->make());
  } else {
    world.fluid_mesh = std::make_unique<TetMesh>(load_mesh(*fluid.mesh, "fluid.mesh"));
    order_along_curve(*world.fluid_mesh);
  }
  // What the fluid step reads of the coupling's (the solver reads these columns in place).
  std::vector<std::string> coupling_reads{coupling::cell::solid_fraction.key(),
                                          coupling::cell::absorption.key(),
                                          coupling::cell::solid_velocity.key()};
  if (spec.dilatation) coupling_reads.push_back(coupling::cell::solid_dilatation.key());
  auto model = std::make_unique<FluidModel>(world.store, *world.fluid_mesh, fluid, substeps,
                                            std::move(coupling_reads));
  FluidModel& f = *model;
  models.fluid = model.get();
  world.models.push_back(std::move(model));
  std::vector<int32_t> well_wall_tets;  // the network's well, whose fluid cells the network owns
  if (models.fracture_flow) well_wall_tets = models.fracture_flow->well_wall_tets();
  auto coupling = std::make_unique<FluidSolidModel>(world.store, solid, f, spec, std::move(adapter),
                                                    std::move(well_wall_tets));
  models.coupling = coupling.get();
  world.models.push_back(std::move(coupling));
}

// Adds a model to the world and returns it, typed.
template <class M>
M* add(World& world, std::unique_ptr<M> model) {
  M* typed = model.get();
  world.models.push_back(std::move(model));
  return typed;
}

}  // namespace

std::unique_ptr<World> build_world(const Scene& scene) {
  auto world = std::make_unique<World>();
  const auto t0 = std::chrono::steady_clock::now();
  // A fluid scene may give its mesh as fluid.mesh; with a solid, the top-level mesh is the solid's.
  const MeshSpec& mesh_spec =
      scene.fluid && scene.fluid->mesh && !scene.solid ? *scene.fluid->mesh : scene.mesh;
  world->mesh = load_mesh(mesh_spec);
  order_along_curve(world->mesh);  // neighbours close in memory (engine/mesh/spatial_order.hpp)
  world->mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  world->mesh_quality = measure_quality(world->mesh);
  StepModels models;
  if (scene.solid)
    models.solid = add(*world, std::make_unique<SolidModel>(world->store, world->mesh, *scene.solid));
  if (scene.fracture_flow)  // right after the solid, whose node pass then reads its crack forces
    models.fracture_flow = add(*world, std::make_unique<FractureFlowModel>(
                                           world->store, *models.solid, world->mesh, *scene.fracture_flow));
  // The continuous meshes only when something consumes them: the adaptive fluid mesh (before the fluid,
  // whose first mesh follows the solid's surface), or an output that asks for the surface.
  auto add_conversion = [&] {
    models.conversion = add(*world, std::make_unique<MeshConversionModel>(
                                        world->store, world->mesh, notch_surfaces(scene.mesh, world->mesh)));
  };
  if (scene.solid && scene.fluid && scene.fluid->adapt) add_conversion();
  if (scene.fluid && scene.solid) {
    add_coupled_fluid(*world, scene, models);
  } else if (scene.fluid) {
    models.fluid = add(*world, std::make_unique<FluidModel>(world->store, world->mesh, *scene.fluid));
  }
  if (scene.solid && scene.output.surface && !models.conversion) add_conversion();
  if (!scene.probes.empty())  // last: it reads what the others created
    world->models.push_back(std::make_unique<ProbeModel>(world->store, scene.probes));
  world->plan = script_step(models);
  return world;
}

}  // namespace rift
