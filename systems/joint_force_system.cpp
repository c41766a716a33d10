#include "systems/joint_force_system.hpp"

#include <algorithm>
#include <cmath>

#include "engine/distributed/share_reduction.hpp"
#include "engine/schedule/parallel.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 1024;

}  // namespace

JointForceSystem::JointForceSystem(Store& store, std::vector<kernels::JointMaterial> materials,
                                   int integration_points, kernels::Softening softening)
    : store_(store),
      materials_(std::move(materials)),
      rule_(&kernels::joint_rule(integration_points)),
      softening_(softening),
      computed_(grain) {
  const size_t joints = store_.table(solid::joint_table).size();
  computed_.set_all(joints);
  blocks_.resize(computed_.blocks());
  breaks_.resize(joints);
  Table& state = store_.add_table(solid::joint_state_table);
  solid::joint_state::damage_onsets.create(state);
  state.resize(1);
}

Access JointForceSystem::access() const {
  namespace joint = solid::joint;
  namespace event = solid::event;
  std::vector<std::string> writes{
      joint::corner_force.key(), joint::d_max.key(),  joint::broken.key(),         joint::opening.key(),
      joint::slip.key(),         joint::damage.key(), joint::stored_energy.key(),  event::step.key(),
      event::time.key(),         event::joint.key(),  event::mode.key(),           event::centroid.key(),
      event::normal.key(),       event::area.key(),   event::released_energy.key()};
  writes.push_back(solid::joint_state::damage_onsets.key());
  if (joint::residual_anchor.exists(store_)) writes.push_back(joint::residual_anchor.key());
  return {{solid::node::x.key(), joint::nodes.key(), joint::material.key(), joint::initial_offset.key()},
          writes,
          {solid::event_table}};  // a break appends its row to the fracture log
}

void JointForceSystem::run(const StepContext& ctx) {
  Table& joints = store_.table(solid::joint_table);
  break_count_.store(0, std::memory_order_relaxed);
  kernels::JointArgs args;
  args.x = solid::node::x.in(store_);
  args.joint_nodes = solid::joint::nodes.in(joints);
  args.material = solid::joint::material.in(joints);
  args.materials = materials_;
  args.rule = rule_;
  args.softening = softening_;
  args.d_max = solid::joint::d_max.in(joints);
  args.broken = solid::joint::broken.in(joints);
  args.corner_force = solid::joint::corner_force.in(joints);
  if (ctx.observed) {  // only outputs, metrics and the energy checks read these (StepContext::observed)
    args.opening = solid::joint::opening.in(joints);
    args.slip = solid::joint::slip.in(joints);
    args.damage = solid::joint::damage.in(joints);
    args.stored_energy = solid::joint::stored_energy.in(joints);
  }
  args.initial_offset = solid::joint::initial_offset.in(joints);
  if (solid::joint::residual_anchor.exists(store_))
    args.residual_anchor = solid::joint::residual_anchor.in(joints);
  args.breaks = breaks_;
  args.break_count = &break_count_;
  std::fill(blocks_.begin(), blocks_.end(), kernels::JointStatus{});
  computed_.parallel_runs(
      [&](size_t b, size_t begin, size_t end) { blocks_[b] += kernels::joint_forces(args, begin, end); });
  kernels::JointStatus total;
  for (const auto& b : blocks_) total += b;  // counts: any order
  degenerate_ = total.degenerate;
  short_softening_ = total.short_softening;
  if (total.damage_onsets > 0 && !share_)
    solid::joint_state::damage_onsets.in(store_)[0] += static_cast<int64_t>(total.damage_onsets);
  if (total.broke > 0) record_events(ctx, std::min(break_count_.load(), breaks_.size()));
}

void JointForceSystem::compute_only(std::span<const int32_t> joints) {
  computed_.keep_only(joints);
  blocks_.assign(computed_.blocks(), {});
}

namespace {
// The integration points of `joints` whose damage history has left 0.
int64_t damaged_points(std::span<const double> history, size_t points, std::span<const int32_t> joints) {
  int64_t n = 0;
  for (int32_t j : joints)
    for (size_t q = 0; q < points; ++q) n += history[size_t(j) * points + q] > 0.0;
  return n;
}
}  // namespace

void JointForceSystem::count_only(std::vector<int32_t> counted) {
  const std::span<const double> history = solid::joint::d_max.read(store_);  // whole at set-up
  damaged_points_at_share_ = std::count_if(history.begin(), history.end(), [](double d) { return d > 0.0; });
  onsets_at_share_ = solid::joint_state::damage_onsets.read(store_)[0];
  counted_ = std::move(counted);
  share_ = true;
}

void JointForceSystem::book_share(const ShareReduction& ranks) {
  const std::span<const double> history = solid::joint::d_max.read(store_);
  const size_t joints = store_.table(solid::joint_table).size();
  int64_t damaged[1] = {damaged_points(history, joints > 0 ? history.size() / joints : 0, counted_)};
  ranks.sum(damaged);
  solid::joint_state::damage_onsets.in(store_)[0] = onsets_at_share_ + damaged[0] - damaged_points_at_share_;
}

// Threads append breaks in any order; sorting by joint makes the log independent of the schedule.
void JointForceSystem::record_events(const StepContext& ctx, size_t count) {
  std::sort(breaks_.begin(), breaks_.begin() + static_cast<std::ptrdiff_t>(count),
            [](const kernels::JointBreak& a, const kernels::JointBreak& b) { return a.joint < b.joint; });
  Table& events = store_.table(solid::event_table);
  const size_t first = events.size();
  events.resize(first + count);
  const auto x = solid::node::x.read(store_);
  const auto nodes = solid::joint::nodes.read(store_);
  auto step = solid::event::step.in(events);
  auto time = solid::event::time.in(events);
  auto joint = solid::event::joint.in(events);
  auto mode = solid::event::mode.in(events);
  auto centroid = solid::event::centroid.in(events);
  auto normal = solid::event::normal.in(events);
  auto area = solid::event::area.in(events);
  auto released = solid::event::released_energy.in(events);
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
