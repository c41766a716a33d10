#include "systems/tet_force_system.hpp"

#include <algorithm>

#include "engine/schedule/parallel.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 1024;

// [begin, end) cut at the multiples of grain.
void add_runs(size_t begin, size_t end, std::vector<std::pair<size_t, size_t>>& runs) {
  while (begin < end) {
    const size_t stop = std::min(end, (begin / grain + 1) * grain);
    runs.emplace_back(begin, stop);
    begin = stop;
  }
}
}  // namespace

TetForceSystem::Tally& TetForceSystem::Tally::operator+=(const Tally& o) {
  if (o.status.first_inverted >= 0 &&
      (status.first_inverted < 0 || o.status.first_inverted < status.first_inverted))
    status.first_inverted = o.status.first_inverted;
  status.inverted += o.status.inverted;
  viscous_power += o.viscous_power;
  return *this;
}

TetForceSystem::TetForceSystem(Store& store, std::vector<kernels::TetMaterial> materials,
                               std::vector<double> initial_stress)
    : store_(store), materials_(std::move(materials)), initial_stress_(std::move(initial_stress)) {
  add_runs(0, store_.table(solid::tet_table).size(), own_runs_);
  set_blocks();
}

// Runs of the same grain-aligned stretch of tets form a block: without hand_over, exactly the blocks of
// parallel_for(tets, grain).
void TetForceSystem::set_blocks() {
  block_first_run_.clear();
  for (size_t r = 0; r < own_runs_.size(); ++r)
    if (r == 0 || own_runs_[r].first / grain != own_runs_[r - 1].first / grain) block_first_run_.push_back(r);
  block_first_run_.push_back(own_runs_.size());
  tallies_.assign(block_first_run_.size() - 1, Tally{});
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
  parallel_for(tallies_.size(), 1, [&](size_t b, size_t) {
    Tally& t = tallies_[b];
    t = Tally{};
    for (size_t r = block_first_run_[b]; r < block_first_run_[b + 1]; ++r) {
      const auto [begin, end] = own_runs_[r];
      Tally run;
      run.status = kernels::tet_forces(a, begin, end);
      for (size_t e = begin; e < end; ++e) run.viscous_power += a.viscous_power[e];
      t += run;
    }
  });
  inverted_ = 0;
  first_inverted_ = -1;
  Tally total;
  for (const Tally& t : tallies_) total += t;  // fixed block order: deterministic
  book(ctx, total);
}

void TetForceSystem::book(const StepContext& ctx, const Tally& tally) {
  Tally seen;
  seen.status = {inverted_, first_inverted_};
  seen += tally;
  inverted_ = seen.status.inverted;
  first_inverted_ = seen.status.first_inverted;
  // The damping force of this step acts over dt (the work integral's rectangle rule).
  solid::energy::damping.in(store_)[0] += ctx.dt * tally.viscous_power;
}

void TetForceSystem::hand_over(const std::vector<std::pair<size_t, size_t>>& ranges) {
  own_runs_.clear();
  size_t next = 0;
  for (const auto& [begin, end] : ranges) {
    add_runs(next, begin, own_runs_);
    next = end;
  }
  add_runs(next, store_.table(solid::tet_table).size(), own_runs_);
  set_blocks();
}

void TetForceSystem::fused_forces(kernels::TetForceArgs a, size_t begin, size_t end,
                                  std::span<double> scratch, Tally& tally) {
  a.corner_force = scratch;
  a.corner_force_first = begin;
  Tally t;
  t.status = kernels::tet_forces(a, begin, end);
  for (size_t e = begin; e < end; ++e) t.viscous_power += a.viscous_power[e];
  tally += t;
}

}  // namespace rift
