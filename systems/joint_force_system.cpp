#include "systems/joint_force_system.hpp"

#include <algorithm>
#include <cmath>

#include "engine/schedule/parallel.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 1024;
}

JointForceSystem::JointForceSystem(Store& store, std::vector<kernels::JointMaterial> materials,
                                   int integration_points, kernels::Softening softening)
    : store_(store),
      materials_(std::move(materials)),
      rule_(&kernels::joint_rule(integration_points)),
      softening_(softening) {
  const size_t joints = store_.table(solid::joint_table).size();
  blocks_.resize((joints + grain - 1) / grain);
  breaks_.resize(joints);
  Table& state = store_.add_table(solid::joint_state_table);
  state.add<int64_t>("damage_onsets");
  state.resize(1);
}

Access JointForceSystem::access() const {
  using solid::col;
  const char* J = solid::joint_table;
  const char* V = solid::event_table;
  std::vector<std::string> writes{col(J, "corner_force"),  col(J, "d_max"), col(J, "broken"),
                                  col(J, "opening"),       col(J, "slip"),  col(J, "damage"),
                                  col(J, "stored_energy"), col(V, "step"),  col(V, "time"),
                                  col(V, "joint"),         col(V, "mode"),  col(V, "centroid"),
                                  col(V, "normal"),        col(V, "area"),  col(V, "released_energy")};
  writes.push_back(col(solid::joint_state_table, "damage_onsets"));
  if (store_.table(J).has("residual_anchor")) writes.push_back(col(J, "residual_anchor"));
  return {{col(solid::node_table, "x"), col(J, "nodes"), col(J, "material"), col(J, "initial_offset")},
          writes,
          {V}};  // a break appends its row to the fracture log
}

void JointForceSystem::run(const StepContext& ctx) {
  Table& joints = store_.table(solid::joint_table);
  break_count_.store(0, std::memory_order_relaxed);
  kernels::JointArgs args;
  args.x = store_.table(solid::node_table).span<double>("x");
  args.joint_nodes = joints.span<int32_t>("nodes");
  args.material = joints.span<int32_t>("material");
  args.materials = materials_;
  args.rule = rule_;
  args.softening = softening_;
  args.d_max = joints.span<double>("d_max");
  args.broken = joints.span<uint8_t>("broken");
  args.corner_force = joints.span<double>("corner_force");
  if (ctx.observed) {  // only outputs, metrics and the energy checks read these (StepContext::observed)
    args.opening = joints.span<double>("opening");
    args.slip = joints.span<double>("slip");
    args.damage = joints.span<double>("damage");
    args.stored_energy = joints.span<double>("stored_energy");
  }
  args.initial_offset = joints.span<double>("initial_offset");
  if (joints.has("residual_anchor")) args.residual_anchor = joints.span<double>("residual_anchor");
  args.breaks = breaks_;
  args.break_count = &break_count_;
  parallel_for(joints.size(), grain, [&](size_t begin, size_t end) {
    blocks_[begin / grain] = kernels::joint_forces(args, begin, end);
  });
  kernels::JointStatus total;
  for (const auto& b : blocks_) total += b;
  degenerate_ = total.degenerate;
  short_softening_ = total.short_softening;
  if (total.damage_onsets > 0)
    store_.table(solid::joint_state_table).span<int64_t>("damage_onsets")[0] +=
        static_cast<int64_t>(total.damage_onsets);
  if (total.broke > 0) record_events(ctx, std::min(break_count_.load(), breaks_.size()));
}

// Threads append breaks in any order; sorting by joint makes the log independent of the schedule.
void JointForceSystem::record_events(const StepContext& ctx, size_t count) {
  std::sort(breaks_.begin(), breaks_.begin() + static_cast<std::ptrdiff_t>(count),
            [](const kernels::JointBreak& a, const kernels::JointBreak& b) { return a.joint < b.joint; });
  Table& events = store_.table(solid::event_table);
  const size_t first = events.size();
  events.resize(first + count);
  const auto x = store_.table(solid::node_table).span<const double>("x");
  const auto nodes = store_.table(solid::joint_table).span<const int32_t>("nodes");
  auto step = events.span<int64_t>("step");
  auto time = events.span<double>("time");
  auto joint = events.span<int32_t>("joint");
  auto mode = events.span<uint8_t>("mode");
  auto centroid = events.span<double>("centroid");
  auto normal = events.span<double>("normal");
  auto area = events.span<double>("area");
  auto released = events.span<double>("released_energy");
  for (size_t k = 0; k < count; ++k) {
    const size_t row = first + k;
    const int32_t j = breaks_[k].joint;
    double m[3][3];  // mid-surface corners
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c)
        m[i][c] = 0.5 * (x[3 * nodes[6 * j + i] + c] + x[3 * nodes[6 * j + i + 3] + c]);
    const double a[3] = {m[1][0] - m[0][0], m[1][1] - m[0][1], m[1][2] - m[0][2]};
    const double b[3] = {m[2][0] - m[0][0], m[2][1] - m[0][1], m[2][2] - m[0][2]};
    const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    step[row] = ctx.step;
    time[row] = ctx.time;
    joint[row] = j;
    mode[row] = static_cast<uint8_t>(breaks_[k].mode);
    for (int c = 0; c < 3; ++c) {
      centroid[3 * row + c] = (m[0][c] + m[1][c] + m[2][c]) / 3.0;
      normal[3 * row + c] = len > 0 ? n[c] / len : 0.0;
    }
    area[row] = 0.5 * len;
    released[row] = breaks_[k].released_energy;
  }
}

}  // namespace rift
