#include "systems/tet_force_system.hpp"

#include "engine/schedule/parallel.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 1024;
}

TetForceSystem::TetForceSystem(Store& store, std::vector<kernels::TetMaterial> materials)
    : store_(store), materials_(std::move(materials)) {
  const size_t tets = store_.table(solid::tet_table).size();
  block_status_.resize((tets + grain - 1) / grain);
}

Access TetForceSystem::access() const {
  using solid::col;
  const char* T = solid::tet_table;
  return {{col(solid::node_table, "x"), col(solid::node_table, "v"), col(T, "nodes"), col(T, "dm_inv"),
           col(T, "volume0"), col(T, "material")},
          {col(T, "corner_force"), col(T, "stress"), col(T, "energy")}};
}

void TetForceSystem::run(const StepContext&) {
  Table& nodes = store_.table(solid::node_table);
  Table& tets = store_.table(solid::tet_table);
  const kernels::TetForceArgs args{nodes.span<double>("x"),
                                   nodes.span<double>("v"),
                                   tets.span<int32_t>("nodes"),
                                   tets.span<double>("dm_inv"),
                                   tets.span<double>("volume0"),
                                   tets.span<int32_t>("material"),
                                   materials_,
                                   tets.span<double>("corner_force"),
                                   tets.span<double>("stress"),
                                   tets.span<double>("energy")};
  parallel_for(tets.size(), grain, [&](size_t begin, size_t end) {
    block_status_[begin / grain] = kernels::tet_forces(args, begin, end);
  });
  inverted_ = 0;
  first_inverted_ = -1;
  for (const auto& s : block_status_) {
    inverted_ += s.inverted;
    if (first_inverted_ < 0 && s.first_inverted >= 0) first_inverted_ = s.first_inverted;
  }
}

}  // namespace rift
