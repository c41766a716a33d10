#include "engine/mesh/block_assembly.hpp"

#include <set>

#include "engine/core/error.hpp"
#include "engine/mesh/box_generator.hpp"
#include "engine/mesh/lattice_box.hpp"

namespace rift {
namespace {

// The box of the block at the origin, meshed by CGAL Mesh_3 at one element size (box_generator.hpp): the
// same surfaces xmin ... zmax as the lattice, and the same mesh for the same block.
TetMesh unstructured_block(const BlockSpec& b) {
  MeshGenerateSpec spec;
  spec.shape = MeshGenerateSpec::Shape::box;
  spec.size = b.size;
  spec.size_min = spec.size_max = *b.element_size;
  spec.max_elements_key = "mesh.max_elements (block '" + b.name + "')";
  return generate_box_mesh(spec);
}

}  // namespace

TetMesh generate_block_assembly(const std::vector<BlockSpec>& blocks) {
  TetMesh out;
  std::set<std::string> names;
  for (const BlockSpec& b : blocks) {
    if (b.name.empty() || !names.insert(b.name).second)
      throw Error("mesh.generate.blocks: block name '" + b.name + "' is empty or used twice");
    const TetMesh m = b.element_size ? unstructured_block(b) : generate_lattice_box(b.cells, b.size);
    const auto offset = static_cast<int32_t>(out.nodes.size());
    for (const auto& x : m.nodes)
      out.nodes.push_back({x[0] + b.origin[0], x[1] + b.origin[1], x[2] + b.origin[2]});
    const auto region = static_cast<int32_t>(out.region_names.size());
    out.region_names.push_back(b.name);
    for (const auto& t : m.tets) {
      out.tets.push_back({t[0] + offset, t[1] + offset, t[2] + offset, t[3] + offset});
      out.tet_region.push_back(region);
    }
    const auto surface0 = static_cast<int32_t>(out.surface_names.size());
    for (const auto& s : m.surface_names) out.surface_names.push_back(b.name + "_" + s);
    for (size_t i = 0; i < m.triangles.size(); ++i) {
      const auto& t = m.triangles[i];
      out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
      out.triangle_surface.push_back(surface0 + m.triangle_surface[i]);
    }
  }
  return out;
}

}  // namespace rift
