#include "systems/node_integration_system.hpp"

#include "engine/schedule/parallel.hpp"
#include "kernels/node_integration.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 4096;
}

NodeIntegrationSystem::NodeIntegrationSystem(Store& store, std::vector<SolidBoundarySpec> conditions,
                                             std::array<double, 3> gravity, TimeFunction mass_damping)
    : store_(store),
      conditions_(std::move(conditions)),
      gravity_(gravity),
      mass_damping_(std::move(mass_damping)),
      damped_(mass_damping_.highest() > 0.0) {
  prescribed_.assign(3 * std::max<size_t>(conditions_.size(), 1), 0.0);
  const size_t nodes = store_.table(solid::node_table).size();
  contact_ = store_.table(solid::node_table).has("contact_force");
  crack_ = store_.table(solid::node_table).has("crack_force");
  blocks_.resize((nodes + grain - 1) / grain);
}

Access NodeIntegrationSystem::access() const {
  using solid::col;
  const char* N = solid::node_table;
  std::vector<std::string> reads{col(solid::tet_table, "corner_force"),
                                 col(solid::face_table, "corner_force"),
                                 col(N, "mass"),
                                 col(N, "inv_mass"),
                                 col(N, "free"),
                                 col(N, "held"),
                                 col(N, "slots"),
                                 col(solid::slot_table, "slot")};
  if (store_.has(solid::joint_table)) reads.push_back(col(solid::joint_table, "corner_force"));
  const char* E = solid::energy_table;
  std::vector<std::string> writes{col(N, "x"),        col(N, "v"),
                                  col(N, "f"),        col(E, "external_work"),
                                  col(E, "tet_work"), col(E, "joint_work")};
  if (contact_) {
    reads.push_back(col(N, "contact_force"));
    writes.push_back(col(E, "contact_work"));
  }
  if (!external_column_.empty()) reads.push_back(col(N, external_column_.c_str()));
  if (crack_) reads.push_back(col(N, "crack_force"));
  if (damped_) writes.push_back(col(E, "damping"));
  return {reads, writes};
}

void NodeIntegrationSystem::run(const StepContext& ctx) {
  // The new velocity lives at t + dt/2, so prescribed velocities are evaluated there.
  for (size_t i = 0; i < conditions_.size(); ++i) {
    const SolidBoundarySpec& c = conditions_[i];
    const double scale =
        c.kind == SolidBoundarySpec::Kind::velocity ? c.function(ctx.time + 0.5 * ctx.dt) : 0.0;
    for (int k = 0; k < 3; ++k) prescribed_[3 * i + k] = c.direction[k] * scale;
  }
  Table& nodes = store_.table(solid::node_table);
  const kernels::NodeIntegrationArgs args{
      ctx.dt,
      {gravity_[0], gravity_[1], gravity_[2]},
      nodes.span<double>("x"),
      nodes.span<double>("v"),
      ctx.observed ? nodes.span<double>("f") : std::span<double>{},  // read by outputs and reactions only
      nodes.span<double>("mass"),
      nodes.span<double>("inv_mass"),
      nodes.span<uint8_t>("free"),
      nodes.span<int32_t>("held"),
      prescribed_,
      contact_ ? nodes.span<double>("contact_force") : std::span<double>{},
      mass_damping_(ctx.time),
      external_column_.empty() ? std::span<const double>{} : nodes.span<double>(external_column_),
      crack_ ? nodes.span<double>("crack_force") : std::span<double>{}};
  const Table& tets = store_.table(solid::tet_table);
  const Table* joints = store_.has(solid::joint_table) ? &store_.table(solid::joint_table) : nullptr;
  const Table& faces = store_.table(solid::face_table);
  const int64_t tet_slots = 4 * static_cast<int64_t>(tets.size());
  const int64_t joint_slots = joints ? 6 * static_cast<int64_t>(joints->size()) : 0;
  const kernels::ForceSlots slots{
      {tets.span<double>("corner_force"), joints ? joints->span<double>("corner_force") : std::span<double>{},
       faces.span<double>("corner_force")},
      {0, tet_slots, tet_slots + joint_slots,
       tet_slots + joint_slots + 3 * static_cast<int64_t>(faces.size())},  // crack faces have no slots
      nodes.span<int32_t>("slots"),
      store_.table(solid::slot_table).span<int32_t>("slot")};
  parallel_for(nodes.size(), grain, [&](size_t begin, size_t end) {
    blocks_[begin / grain] = kernels::integrate_nodes(args, slots, begin, end);
  });
  kernels::NodeStepResult total;
  for (const auto& b : blocks_) total += b;  // fixed block order: deterministic
  non_finite_ = total.non_finite;
  Table& energy = store_.table(solid::energy_table);
  energy.span<double>("tet_work")[0] += total.work[0];
  energy.span<double>("joint_work")[0] += total.work[1];
  energy.span<double>("external_work")[0] += total.work[2];
  if (contact_) energy.span<double>("contact_work")[0] += total.work[3];
  if (damped_) energy.span<double>("damping")[0] += total.damping;
}

}  // namespace rift
