#include "systems/surface_load_system.hpp"

#include "engine/schedule/parallel.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

SurfaceLoadSystem::SurfaceLoadSystem(Store& store, std::vector<SolidBoundarySpec> loads,
                                     std::array<double, 6> initial_stress)
    : store_(store), specs_(std::move(loads)), initial_stress_(initial_stress), values_(specs_.size()) {}

Access SurfaceLoadSystem::access() const {
  using solid::col;
  const char* F = solid::face_table;
  return {{col(solid::node_table, "x"), col(F, "nodes"), col(F, "load")}, {col(F, "corner_force")}};
}

void SurfaceLoadSystem::run(const StepContext& ctx) {
  // Loads act at the start of the step: the central-difference force is evaluated at time t.
  for (size_t i = 0; i < specs_.size(); ++i) {
    const SolidBoundarySpec& s = specs_[i];
    const double scale = s.function(ctx.time);
    kernels::FaceLoad& L = values_[i];
    L = {};
    if (s.kind == SolidBoundarySpec::Kind::pressure)
      L.pressure = scale;
    else if (s.kind == SolidBoundarySpec::Kind::in_situ)
      for (int c = 0; c < 6; ++c) L.stress[c] = initial_stress_[c] * scale;
    else
      for (int c = 0; c < 3; ++c) L.traction[c] = s.direction[c] * scale;
  }
  Table& faces = store_.table(solid::face_table);
  const auto x = store_.table(solid::node_table).span<double>("x");
  parallel_for(faces.size(), 2048, [&](size_t begin, size_t end) {
    kernels::surface_loads(x, faces.span<int32_t>("nodes"), faces.span<int32_t>("load"), values_,
                           faces.span<double>("corner_force"), begin, end);
  });
}

}  // namespace rift
