#include "systems/tet_force_system.hpp"

#include "engine/schedule/parallel.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 1024;
}

TetForceSystem::TetForceSystem(Store& store, std::vector<kernels::TetMaterial> materials,
                               std::vector<double> initial_stress)
    : store_(store), materials_(std::move(materials)), initial_stress_(std::move(initial_stress)) {
  const size_t tets = store_.table(solid::tet_table).size();
  blocks_.resize((tets + grain - 1) / grain);
}

Access TetForceSystem::access() const {
  using solid::col;
  const char* T = solid::tet_table;
  return {{col(solid::node_table, "x"), col(solid::node_table, "v"), col(T, "nodes"), col(T, "dm_inv"),
           col(T, "volume0"), col(T, "material")},
          {col(T, "corner_force"), col(T, "stress"), col(T, "energy"), col(T, "viscous_power"),
           col(solid::energy_table, "damping")}};
}

void TetForceSystem::run(const StepContext& ctx) {
  Table& nodes = store_.table(solid::node_table);
  Table& tets = store_.table(solid::tet_table);
  kernels::TetForceArgs args{nodes.span<double>("x"), nodes.span<double>("v"), tets.span<int32_t>("nodes"),
                             tets.span<double>("dm_inv"), tets.span<double>("volume0"),
                             tets.span<int32_t>("material"), materials_, tets.span<double>("corner_force"),
                             // Only outputs and the energy checks read these (StepContext::observed).
                             ctx.observed ? tets.span<double>("stress") : std::span<double>{},
                             ctx.observed ? tets.span<double>("energy") : std::span<double>{}};
  const auto power = tets.span<double>("viscous_power");
  args.viscous_power = power;
  args.initial_stress = initial_stress_;
  parallel_for(tets.size(), grain, [&](size_t begin, size_t end) {
    Block& b = blocks_[begin / grain];
    b.status = kernels::tet_forces(args, begin, end);
    b.viscous_power = 0.0;
    for (size_t e = begin; e < end; ++e) b.viscous_power += power[e];
  });
  inverted_ = 0;
  first_inverted_ = -1;
  double viscous_power = 0.0;
  for (const auto& b : blocks_) {  // fixed block order: deterministic
    inverted_ += b.status.inverted;
    if (first_inverted_ < 0 && b.status.first_inverted >= 0) first_inverted_ = b.status.first_inverted;
    viscous_power += b.viscous_power;
  }
  // The damping force of this step acts over dt (the work integral's rectangle rule).
  store_.table(solid::energy_table).span<double>("damping")[0] += ctx.dt * viscous_power;
}

}  // namespace rift
