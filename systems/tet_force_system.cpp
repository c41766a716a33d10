#include "systems/tet_force_system.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

#include "engine/distributed/share_reduction.hpp"
#include "engine/schedule/parallel.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 1024;
constexpr size_t damping_grain = 16 * grain;  // the damping's sum: one column of 8 B a tet

double largest_abs(std::span<const double> x, size_t begin, size_t end) {
  double m = 0.0;
  for (size_t e = begin; e < end; ++e) m = std::max(m, std::abs(x[e]));
  return m;
}
}  // namespace

TetForceSystem::Tally& TetForceSystem::Tally::operator+=(const Tally& o) {
  if (o.status.first_inverted >= 0 &&
      (status.first_inverted < 0 || o.status.first_inverted < status.first_inverted))
    status.first_inverted = o.status.first_inverted;
  status.inverted += o.status.inverted;
  largest_viscous_power = std::max(largest_viscous_power, o.largest_viscous_power);
  return *this;
}

TetForceSystem::TetForceSystem(Store& store, std::vector<kernels::TetMaterial> materials,
                               std::vector<double> initial_stress)
    : store_(store),
      materials_(std::move(materials)),
      initial_stress_(std::move(initial_stress)),
      own_(grain) {
  const size_t tets = store_.table(solid::tet_table).size();
  own_.set_all(tets);
  tallies_.assign(own_.blocks(), Tally{});
  damping_parts_.resize((tets + damping_grain - 1) / damping_grain);
}

Access TetForceSystem::access() const {
  return {{solid::node::x.key(), solid::node::v.key(), solid::tet::nodes.key(), solid::tet::dm_inv.key(),
           solid::tet::volume0.key(), solid::tet::material.key()},
          {solid::tet::corner_force.key(), solid::tet::stress.key(), solid::tet::energy.key(),
           solid::tet::viscous_power.key(), solid::energy::damping.key()}};
}

Access TetForceSystem::fused_access() const {
  Access a = access();
  std::erase(a.writes, solid::tet::corner_force.key());
  return a;
}

kernels::TetForceArgs TetForceSystem::step_args(const StepContext& ctx) const {
  Table& nodes = store_.table(solid::node_table);
  Table& tets = store_.table(solid::tet_table);
  kernels::TetForceArgs a{solid::node::x.in(nodes), solid::node::v.in(nodes), solid::tet::nodes.in(tets),
                          solid::tet::dm_inv.in(tets), solid::tet::volume0.in(tets),
                          solid::tet::material.in(tets), materials_, solid::tet::corner_force.in(tets),
                          // Only outputs and the energy checks read these (StepContext::observed).
                          ctx.observed ? solid::tet::stress.in(tets) : std::span<double>{},
                          ctx.observed ? solid::tet::energy.in(tets) : std::span<double>{}};
  a.viscous_power = solid::tet::viscous_power.in(tets);
  a.initial_stress = initial_stress_;
  return a;
}

void TetForceSystem::run(const StepContext& ctx) {
  const kernels::TetForceArgs a = step_args(ctx);
  std::fill(tallies_.begin(), tallies_.end(), Tally{});
  own_.parallel_runs([&](size_t b, size_t begin, size_t end) {
    Tally run;
    run.status = kernels::tet_forces(a, begin, end);
    run.largest_viscous_power = largest_abs(a.viscous_power, begin, end);
    tallies_[b] += run;
  });
  inverted_ = 0;
  first_inverted_ = -1;
  largest_viscous_power_ = 0.0;
  Tally total;
  for (const Tally& t : tallies_) total += t;
  book(total);
  if (!handed_over_ && !share_) book_damping(ctx);
}

void TetForceSystem::book(const Tally& tally) {
  Tally seen;
  seen.status = {inverted_, first_inverted_};
  seen.largest_viscous_power = largest_viscous_power_;
  seen += tally;
  inverted_ = seen.status.inverted;
  first_inverted_ = seen.status.first_inverted;
  largest_viscous_power_ = seen.largest_viscous_power;
}

// The damping force of this step acts over dt (the work integral's rectangle rule). Every power is a
// multiple of the grid's quantum once pre-rounded, so the blocks' sums merge exactly in any order.
void TetForceSystem::book_damping(const StepContext& ctx) {
  const std::span<const double> power = solid::tet::viscous_power.read(store_);
  const kernels::ReproducibleGrid grid =
      kernels::reproducible_grid(largest_viscous_power_, static_cast<int64_t>(power.size()));
  parallel_for(power.size(), damping_grain, [&](size_t begin, size_t end) {
    kernels::ReproducibleSum part;
    for (size_t e = begin; e < end; ++e) part.add(power[e], grid);
    damping_parts_[begin / damping_grain] = part;
  });
  kernels::ReproducibleSum total;
  for (const auto& part : damping_parts_) total += part;
  book_damping_power(ctx.dt, total.value());
}

// dt times the step's summed power, into the damping book, in one rounding (an explicit fused multiply-add):
// left to the compiler, whether `damping += dt * power` is contracted depended on the code around it, and a
// change elsewhere in the file moved the book's last bits.
void TetForceSystem::book_damping_power(double dt, double power) {
  double& damping = solid::energy::damping.in(store_)[0];
  damping = std::fma(dt, power, damping);
}

void TetForceSystem::hand_over(const std::vector<std::pair<size_t, size_t>>& ranges) {
  std::vector<RunBlocks::Run> kept;  // the ranges between the handed-over ones
  size_t next = 0;
  for (const auto& [begin, end] : ranges) {
    kept.emplace_back(next, begin);
    next = end;
  }
  kept.emplace_back(next, store_.table(solid::tet_table).size());
  own_.set(kept);
  tallies_.assign(own_.blocks(), Tally{});
  handed_over_ = !ranges.empty();
}

void TetForceSystem::count_only(std::vector<int32_t> counted) {
  counted_ = std::move(counted);
  share_ = true;
}

// As book_damping, over the counted tets, with the grid and the sum taken over the ranks. The inverted
// tets are added over the ranks as each saw them: a tet across a boundary, computed on each side, counts
// once per side in the guard's message; the lowest index, and so whether the guard stops, are one process's.
void TetForceSystem::book_share(const StepContext& ctx, const ShareReduction& ranks) {
  double largest = largest_viscous_power_;
  ranks.max({&largest, 1});
  const std::span<const double> power = solid::tet::viscous_power.read(store_);
  const kernels::ReproducibleGrid grid =
      kernels::reproducible_grid(largest, static_cast<int64_t>(power.size()));
  kernels::ReproducibleSum total;
  for (int32_t e : counted_) total.add(power[size_t(e)], grid);
  ranks.sum({&total, 1});
  book_damping_power(ctx.dt, total.value());
  int64_t inverted[1] = {static_cast<int64_t>(inverted_)};
  int64_t first[1] = {first_inverted_ < 0 ? INT64_MAX : first_inverted_};
  ranks.sum(inverted);
  ranks.min(first);
  inverted_ = static_cast<size_t>(inverted[0]);
  first_inverted_ = first[0] == INT64_MAX ? -1 : first[0];
}

void TetForceSystem::compute_only(std::span<const int32_t> tets) {
  own_.keep_only(tets);
  tallies_.assign(own_.blocks(), Tally{});
}

void TetForceSystem::fused_forces(kernels::TetForceArgs a, size_t begin, size_t end,
                                  std::span<double> scratch, Tally& tally) {
  a.corner_force = scratch;
  a.corner_force_first = begin;
  Tally t;
  t.status = kernels::tet_forces(a, begin, end);
  t.largest_viscous_power = largest_abs(a.viscous_power, begin, end);
  tally += t;
}

}  // namespace rift
