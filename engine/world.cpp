#include "engine/world.hpp"

#include <chrono>
#include <limits>

#include "engine/mesh/block_assembly.hpp"
#include "engine/mesh/box_generator.hpp"
#include "engine/mesh/cylinder_generator.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "engine/mesh/spatial_order.hpp"
#include "engine/mesh/structured_box.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/mesh_conversion_model.hpp"
#include "systems/solid_model.hpp"

namespace rift {

std::vector<System*> World::systems() const {
  std::vector<System*> all;
  for (const auto& m : models)
    for (System* s : m->systems()) all.push_back(s);
  return all;
}

double World::stable_dt() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& m : models) dt = std::min(dt, m->stable_dt());
  return dt;
}

TetMesh load_mesh(const MeshSpec& spec) {
  if (spec.file) return read_msh(*spec.file, spec.scale);
  if (spec.generate->shape == MeshGenerateSpec::Shape::blocks)
    return generate_block_assembly(spec.generate->blocks);
  if (spec.generate->cells) {
    StructuredBoxSpec box;
    box.lo = spec.generate->origin;
    for (int d = 0; d < 3; ++d) box.hi[d] = box.lo[d] + spec.generate->size[d];
    box.cells = *spec.generate->cells;
    return structured_box(box);
  }
  if (spec.generate->shape == MeshGenerateSpec::Shape::cylinder)
    return generate_cylinder_mesh(*spec.generate);
  return generate_box_mesh(*spec.generate);
}

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

std::unique_ptr<World> build_world(const Scene& scene) {
  auto world = std::make_unique<World>();
  const auto t0 = std::chrono::steady_clock::now();
  // A fluid scene may give its mesh as fluid.mesh (the reader refuses solid and fluid together).
  const MeshSpec& mesh_spec = scene.fluid && scene.fluid->mesh ? *scene.fluid->mesh : scene.mesh;
  world->mesh = load_mesh(mesh_spec);
  order_along_curve(world->mesh);  // neighbours close in memory (engine/mesh/spatial_order.hpp)
  world->mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  world->mesh_quality = measure_quality(world->mesh);
  if (scene.solid)
    world->models.push_back(std::make_unique<SolidModel>(world->store, world->mesh, *scene.solid));
  if (scene.fluid)
    world->models.push_back(std::make_unique<FluidModel>(world->store, world->mesh, *scene.fluid));
  // The continuous meshes only when something consumes them (today: an output that asks for the surface).
  if (scene.solid && scene.output.surface)
    world->models.push_back(std::make_unique<MeshConversionModel>(world->store, world->mesh,
                                                                  notch_surfaces(scene.mesh, world->mesh)));
  return world;
}

}  // namespace rift
