#include "systems/coupling/fluid_mesh_adapter.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <vector>

#include "engine/mesh/spatial_order.hpp"
#include "systems/mesh_conversion_model.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

FluidMeshAdapter::FluidMeshAdapter(const Store& store, MeshConversionModel& conversion,
                                   const MeshGenerateSpec& box, const FluidAdaptSpec& spec)
    : store_(store),
      conversion_(conversion),
      interval_(spec.interval),
      tags_{spec.boundary, spec.notch, spec.fracture} {
  for (int d = 0; d < 3; ++d) {
    box_.lo[d] = box.origin[d];
    box_.hi[d] = box.origin[d] + box.size[d];
  }
  box_.size_min = box.size_min;
  box_.size_max = box.size_max;
  box_.grading = box.grading;
  box_.seed = box.seed;
  box_.max_tets = box.max_elements;
  box_.max_tets_key = box.max_elements_key;
}

TetMesh FluidMeshAdapter::make() {
  const auto t0 = std::chrono::steady_clock::now();
  const MeshConversion& surface = conversion_.conversion();  // caught up with every break so far
  const auto x = solid::node::x.read(store_);
  const auto tri = surface.triangle_nodes();
  const auto tag = surface.triangle_tag();
  std::vector<double> soup;
  soup.reserve(3 * tri.size());
  size_t cracks = 0;
  for (size_t t = 0; t < tag.size(); ++t) {
    if (!tags_[static_cast<int>(tag[t])]) continue;
    cracks += tag[t] == SurfaceTag::fracture;
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d) soup.push_back(x[3 * static_cast<size_t>(tri[3 * t + a]) + d]);
  }
  Mesh3Stats stats;
  TetMesh mesh = generate_graded_box(box_, soup, &stats);
  order_along_curve(mesh);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  seconds_ += s;
  ++calls_;
  spdlog::info(
      "fluid mesh adapted to the solid's surface ({} triangles, {} of them on cracks): {} nodes, {} tets "
      "in {:.2f} s",
      soup.size() / 9, cracks, mesh.nodes.size(), mesh.tets.size(), s);
  return mesh;
}

}  // namespace rift
