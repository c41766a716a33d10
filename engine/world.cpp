#include "engine/world.hpp"

#include <algorithm>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"
#include "engine/mesh/block_assembly.hpp"
#include "engine/mesh/borehole_box.hpp"
#include "engine/mesh/box_generator.hpp"
#include "engine/mesh/cylinder_generator.hpp"
#include "engine/mesh/element_estimate.hpp"
#include "engine/mesh/graded_axis.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "engine/mesh/structured_box.hpp"

namespace rift {

double World::stable_dt() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& m : models) dt = std::min(dt, m->stable_dt());
  return dt;
}

TetMesh load_mesh(const MeshSpec& spec, const std::string& section) {
  if (spec.file) {
    MshReadStats stats;
    TetMesh mesh =
        read_msh(*spec.file, spec.scale, &stats, {spec.max_file_bytes, section + ".max_file_bytes"});
    // The scene's hash holds the file's content as it was when the scene was read; the mesh is built
    // from exactly those bytes or not at all.
    if (!spec.file_fnv1a64.empty() && hex16(stats.content_fnv1a64) != spec.file_fnv1a64)
      throw Error(*spec.file + ": the mesh file changed after the scene was read (content hash " +
                  spec.file_fnv1a64 + ", now " + hex16(stats.content_fnv1a64) + "); start the run again");
    return mesh;
  }
  check_lattice_budget(*spec.generate);
  if (spec.generate->shape == MeshGenerateSpec::Shape::blocks)
    return generate_block_assembly(spec.generate->blocks);
  if (const auto& hole = spec.generate->borehole)
    return borehole_box(borehole_box_spec(spec.generate->origin, spec.generate->size, *hole));
  if (const auto& g = spec.generate->graded) {
    return structured_box_on_axes(graded_lattice_axes(spec.generate->origin, spec.generate->size, g->fine_min,
                                                      g->fine_max, g->size, g->growth));
  }
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

}  // namespace rift
