#include "systems/coupling/fluid_solid_exchange.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/core/error.hpp"
#include "engine/schedule/parallel.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/fluid_solid_exchange.hpp"
#include "kernels/surface_load.hpp"
#include "systems/coupling/fluid_solid_tables.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/fracture_flow/fracture_flow_tables.hpp"
#include "systems/node_force_route.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t kTetGrain = 4096, kPairGrain = 1024;

// The network inlet's fluid cells and their shares (pairs.inlet_cells, pairs.inlet_shares, summing to 1).
// A point (zero extent): the one cell that holds it. A box: the cells whose centres lie in it, each in
// proportion to the fluid it holds, (1 - alpha_K) |K|: a sink spread over the notch's mouth draws the
// fluid in as the mouth does, where a one-cell sink would pull it through a point at a speed, and a
// Bernoulli drop, no notch has. An error when the point is outside the fluid or the box holds no fluid.
// `pressure` (per node) only serves the interpolation that finds the point's cell.
void find_inlet_cells(const ExchangeSettings& s, std::span<const double> x, std::span<const int32_t> tets,
                      std::span<const double> solid_fraction, std::span<const double> volumes,
                      std::span<const double> pressure, ExchangePairs& pairs) {
  const auto& point = *s.network_inlet;
  const auto& extent = s.network_inlet_extent;
  pairs.inlet_cells.clear();
  pairs.inlet_shares.clear();
  if (extent[0] == 0.0 && extent[1] == 0.0 && extent[2] == 0.0) {
    const std::span<const double> pt(point.data(), 3);
    kernels::coupling_broad_phase({pt, pt, pairs.fluid_lo, pairs.fluid_hi, 0.0}, pairs.inlet_broad);
    double unused = 0.0;
    int32_t found = -1;
    if (kernels::interpolate_p1_at_points(x, tets, pressure, pt, pairs.inlet_broad.pairs, {&unused, 1},
                                          {&found, 1}) > 0)
      throw Error(fmt::format("fluid_solid.network_inlet [{}, {}, {}] is outside the fluid's mesh", point[0],
                              point[1], point[2]));
    pairs.inlet_cells.push_back(found);
    pairs.inlet_shares.push_back(1.0);
    return;
  }
  double fluid = 0.0;
  for (size_t k = 0; k < volumes.size(); ++k) {  // in tet order: deterministic
    bool inside = true;
    for (int d = 0; d < 3 && inside; ++d) {
      double c = 0.0;
      for (int a = 0; a < 4; ++a) c += 0.25 * x[3 * size_t(tets[4 * k + size_t(a)]) + size_t(d)];
      inside = std::abs(c - point[size_t(d)]) <= 0.5 * extent[size_t(d)];
    }
    if (!inside) continue;
    const double w = (1.0 - std::clamp(solid_fraction[k], 0.0, 1.0)) * volumes[k];
    pairs.inlet_cells.push_back(static_cast<int32_t>(k));
    pairs.inlet_shares.push_back(w);
    fluid += w;
  }
  if (fluid <= 0.0)
    throw Error(fmt::format(
        "fluid_solid.network_inlet [{}, {}, {}] with network_inlet_extent [{}, {}, {}]: {} — make the box "
        "larger than the fluid's cells there, or move it into the fluid",
        point[0], point[1], point[2], extent[0], extent[1], extent[2],
        pairs.inlet_cells.empty() ? "no fluid cell has its centre in the box"
                                  : "the cells with their centres in the box are all inside the solid"));
  for (double& share : pairs.inlet_shares) share /= fluid;
}

// The fluid's pressure where it meets the network, in the cells find_inlet_cells chose: the P1 pressure
// at the point (one cell), or the shares' mean of the cells' mean pressures (a box).
double inlet_pressure(const ExchangeSettings& s, std::span<const double> x, std::span<const int32_t> tets,
                      std::span<const double> pressure, const ExchangePairs& pairs) {
  const auto& extent = s.network_inlet_extent;
  if (extent[0] == 0.0 && extent[1] == 0.0 && extent[2] == 0.0) {
    const kernels::CouplingPair in_cell{0, pairs.inlet_cells[0]};
    double value = 0.0;
    kernels::interpolate_p1_at_points(x, tets, pressure, {s.network_inlet->data(), 3}, {&in_cell, 1},
                                      {&value, 1});
    return value;
  }
  double value = 0.0;
  for (size_t i = 0; i < pairs.inlet_cells.size(); ++i) {
    const size_t k = size_t(pairs.inlet_cells[i]);
    double mean = 0.0;
    for (int a = 0; a < 4; ++a) mean += 0.25 * pressure[size_t(tets[4 * k + size_t(a)])];
    value += pairs.inlet_shares[i] * mean;
  }
  return value;
}
}  // namespace

SolidToFluidSystem::SolidToFluidSystem(Store& store, fluid::FluidSolver& solver, ExchangeSettings settings,
                                       ExchangePairs& pairs)
    : store_(store), solver_(solver), settings_(settings), pairs_(pairs) {
  Table& ft = store_.table(fluid::tet_table);
  coupling::cell::solid_volume.create(ft);
  coupling::cell::solid_fraction.create(ft);
  coupling::cell::solid_velocity.create(ft);
  coupling::cell::absorption.create(ft);
  if (settings_.dilatation) {
    coupling::cell::solid_dilatation.create(ft);
    // The solid's volumes at the last exchange, for its mean rate of volume change over each window; at
    // first those of the initial configuration, so the exchange at t = 0 sees no change.
    Table& solid_tets = store_.table(solid::tet_table);
    coupling::solid_tet::volume_at_exchange.create(solid_tets);
    pairs_.solid_dilatation.resize(solid_tets.size());
    kernels::tet_volume_rates(solid::node::x.read(store_), solid::tet::nodes.read(solid_tets), 0.0,
                              coupling::solid_tet::volume_at_exchange.in(solid_tets), pairs_.solid_dilatation,
                              0, solid_tets.size());
  }
  coupling::cell::velocity_before.create(ft);
  if (settings_.network_inlet) coupling::cell::network_cell.create(ft);
  const size_t ns = store_.table(solid::tet_table).size();
  pairs_.solid_ids.resize(ns);
  std::iota(pairs_.solid_ids.begin(), pairs_.solid_ids.end(), 0);
  pairs_.solid_lo.resize(3 * ns);
  pairs_.solid_hi.resize(3 * ns);
  pairs_.solid_velocity.resize(3 * ns);
  fluid_mesh_changed();
}

// The fluid mesh does not move: its boxes once per mesh.
void SolidToFluidSystem::fluid_mesh_changed() {
  const size_t nf = solver_.volumes().size();
  pairs_.fluid_ids.resize(nf);
  std::iota(pairs_.fluid_ids.begin(), pairs_.fluid_ids.end(), 0);
  pairs_.fluid_lo.resize(3 * nf);
  pairs_.fluid_hi.resize(3 * nf);
  kernels::tet_bounding_boxes(solver_.nodes(), solver_.tets(), pairs_.fluid_ids, pairs_.fluid_lo,
                              pairs_.fluid_hi, 0, nf);
  pairs_.fluid_velocity.resize(3 * nf);
  pairs_.first.resize(nf + 1);
  pairs_.pair_weight.resize(nf);
  if (wall_tet_.empty()) return;
  const auto x = solver_.nodes();
  const auto tets = solver_.tets();
  in_rock_box_.assign(nf, 1);
  for (size_t k = 0; k < nf; ++k)
    for (size_t d = 0; d < 3; ++d) {
      double c = 0.0;
      for (size_t a = 0; a < 4; ++a) c += 0.25 * x[3 * size_t(tets[4 * k + a]) + d];
      if (c < rock_box_[d] || c > rock_box_[d + 3]) in_rock_box_[k] = 0;
    }
}

Access SolidToFluidSystem::access() const {
  Access a{{solid::node::x.key(), solid::node::v.key(), solid::tet::nodes.key(), fluid::node::velocity.key()},
           {coupling::cell::solid_volume.key(), coupling::cell::solid_fraction.key(),
            coupling::cell::solid_velocity.key(), coupling::cell::absorption.key(),
            coupling::cell::velocity_before.key(), coupling::state::pairs.key(),
            coupling::state::cut_cells.key(), coupling::state::solid_volume.key()}};
  if (settings_.dilatation)
    for (const std::string& c :
         {coupling::solid_tet::volume_at_exchange.key(), coupling::cell::solid_dilatation.key()})
      a.writes.push_back(c);
  if (settings_.network_inlet) {
    a.reads.push_back(fracture_flow::books::injected.key());
    if (store_.has(solid::joint_table)) {
      a.reads.push_back(solid::joint::broken.key());
      a.reads.push_back(solid::joint::tets.key());
    }
    a.writes.push_back(coupling::cell::network_cell.key());
    a.writes.push_back(coupling::state::inlet_injected.key());
    a.writes.push_back(coupling::state::inlet_sink_mass.key());
  }
  return a;
}

void SolidToFluidSystem::run(const StepContext&) {
  exchange();
}

// The candidate pairs, their overlap volumes and the solid tets' mean velocities, for the solid at node
// positions x with node velocities v.
void SolidToFluidSystem::find_pairs(std::span<const double> x, std::span<const double> v) {
  const auto solid_tets = solid::tet::nodes.in(store_);
  const size_t ns = pairs_.solid_ids.size();
  parallel_for(ns, kTetGrain, [&](size_t b, size_t e) {
    kernels::tet_bounding_boxes(x, solid_tets, pairs_.solid_ids, pairs_.solid_lo, pairs_.solid_hi, b, e);
    kernels::tet_mean_vectors(v, solid_tets, pairs_.solid_velocity, b, e);
  });
  kernels::coupling_broad_phase({pairs_.fluid_lo, pairs_.fluid_hi, pairs_.solid_lo, pairs_.solid_hi, 0.0},
                                pairs_.broad);
  const auto& list = pairs_.broad.pairs;
  const size_t np = list.size();
  if (pairs_.volume.size() < np) {  // grown, never shrunk
    pairs_.volume.resize(np);
    pairs_.penalty.resize(3 * np);
    pairs_.force.resize(3 * np);
  }
  const std::span<double> volume(pairs_.volume.data(), np);
  const kernels::OverlapArgs overlap{solver_.nodes(), solver_.tets(), x, solid_tets, list, volume};
  parallel_for(np, kPairGrain, [&](size_t b, size_t e) { kernels::overlap_volumes(overlap, b, e); });
  kernels::pair_ranges(list, pairs_.first);
}

// The concurrent coupling's fluid_to_solid uses the pairs of the exchange at the window's start, which a
// restart does not have: they are found again from the positions then (x_at_exchange), and the pair
// weights recomputed into scratch. The cells' own values are the checkpoint's and stay untouched.
void SolidToFluidSystem::rebuild_pairs(std::span<const double> x_at_exchange) {
  const auto v = solid::node::v.in(store_);  // only its tet means, unused here
  find_pairs(x_at_exchange, v);
  const size_t nf = pairs_.fluid_ids.size();
  std::vector<double> volume(nf), fraction(nf), target(3 * nf), sigma(nf);
  const kernels::SolidToFluidArgs cells{settings_.rho,
                                        settings_.beta,
                                        settings_.dt,
                                        solver_.volumes(),
                                        pairs_.broad.pairs,
                                        pairs_.first,
                                        {pairs_.volume.data(), pairs_.broad.pairs.size()},
                                        pairs_.solid_velocity,
                                        {},
                                        volume,
                                        fraction,
                                        target,
                                        sigma,
                                        pairs_.pair_weight,
                                        {}};
  parallel_for(nf, kTetGrain, [&](size_t b, size_t e) { kernels::solid_to_fluid_cells(cells, b, e); });
}

void SolidToFluidSystem::exchange() {
  const Table& nodes = store_.table(solid::node_table);
  const auto x = solid::node::x.in(nodes);
  const auto solid_tets = solid::tet::nodes.in(store_);
  const size_t ns = pairs_.solid_ids.size(), nf = pairs_.fluid_ids.size();
  find_pairs(x, solid::node::v.in(nodes));
  if (settings_.dilatation) {
    const auto volume_prev = coupling::solid_tet::volume_at_exchange.in(store_);
    parallel_for(ns, kTetGrain, [&](size_t b, size_t e) {
      kernels::tet_volume_rates(x, solid_tets, settings_.dt, volume_prev, pairs_.solid_dilatation, b, e);
    });
  }
  const auto& list = pairs_.broad.pairs;
  const size_t np = list.size();
  const std::span<double> volume(pairs_.volume.data(), np);

  Table& ft = store_.table(fluid::tet_table);
  const kernels::SolidToFluidArgs cells{
      settings_.rho,
      settings_.beta,
      settings_.dt,
      solver_.volumes(),
      list,
      pairs_.first,
      volume,
      pairs_.solid_velocity,
      pairs_.solid_dilatation,
      coupling::cell::solid_volume.in(ft),
      coupling::cell::solid_fraction.in(ft),
      coupling::cell::solid_velocity.in(ft),
      coupling::cell::absorption.in(ft),
      pairs_.pair_weight,
      settings_.dilatation ? coupling::cell::solid_dilatation.in(ft) : std::span<double>{}};
  const auto fluid_u = fluid::node::velocity.in(store_);
  parallel_for(nf, kTetGrain, [&](size_t b, size_t e) {
    kernels::solid_to_fluid_cells(cells, b, e);
    kernels::tet_mean_vectors(fluid_u, solver_.tets(), coupling::cell::velocity_before.in(ft), b, e);
  });
  if (settings_.network_inlet) {
    network_sink();
    mark_network_cells();
  }
  bind_solver_inputs();

  Table& state = store_.table(coupling::state_table);
  double covered = 0.0;
  size_t cut = 0;
  for (size_t k = 0; k < nf; ++k) {  // in tet order: deterministic
    covered += cells.solid_volume[k];
    cut += cells.fraction[k] > 0.0 && cells.fraction[k] < 1.0;
  }
  coupling::state::pairs.in(state)[0] = static_cast<int64_t>(np);
  coupling::state::cut_cells.in(state)[0] = static_cast<int64_t>(cut);
  coupling::state::solid_volume.in(state)[0] = covered;
}

// What the cracks' network took in since the last exchange (its well's book, kg) leaves the fluid over the
// coming fluid step from the inlet's cells, each its share s_K: div u = -(dm / rho) s_K / (dt |K|) there.
// The books (inlet_injected, inlet_sink_mass) make the two sides' masses agree exactly.
void SolidToFluidSystem::network_sink() {
  Table& state = store_.table(coupling::state_table);
  const double injected = fracture_flow::books::injected.in(store_)[0];
  double& seen = coupling::state::inlet_injected.in(state)[0];
  const double dm = injected - seen;
  seen = injected;
  coupling::state::inlet_sink_mass.in(state)[0] += dm;
  find_inlet_cells(settings_, solver_.nodes(), solver_.tets(), coupling::cell::solid_fraction.in(store_),
                   solver_.volumes(), solver_.pressure(), pairs_);
  auto source = solver_.volume_source();
  std::fill(source.begin(), source.end(), 0.0);
  for (size_t i = 0; i < pairs_.inlet_cells.size(); ++i) {
    const size_t k = static_cast<size_t>(pairs_.inlet_cells[i]);
    source[k] = -(dm / settings_.rho) * pairs_.inlet_shares[i] / (settings_.dt * solver_.volumes()[k]);
  }
}

void SolidToFluidSystem::set_network_wall(std::span<const int32_t> wall_tets) {
  const size_t ns = store_.table(solid::tet_table).size();
  wall_tet_.assign(ns, 0);
  for (int32_t t : wall_tets) wall_tet_[size_t(t)] = 1;
  network_tet_.resize(ns);
  const auto x0 = solid::node::x0.read(store_);
  for (int d = 0; d < 3; ++d) rock_box_[size_t(d)] = rock_box_[size_t(d) + 3] = x0[size_t(d)];
  for (size_t i = 0; i < x0.size(); ++i) {
    rock_box_[i % 3] = std::min(rock_box_[i % 3], x0[i]);
    rock_box_[i % 3 + 3] = std::max(rock_box_[i % 3 + 3], x0[i]);
  }
  fluid_mesh_changed();
}

// fluid_tet.network_cell = 1 where a cell's centre lies in the rock's box at t = 0, or the cell shares
// volume with a tet on the well's wall or beside a broken joint, and it is not one of the inlet's cells
// (those hand the network its fluid: their continuity stays).
void SolidToFluidSystem::mark_network_cells() {
  std::copy(wall_tet_.begin(), wall_tet_.end(), network_tet_.begin());
  if (store_.has(solid::joint_table)) {
    const Table& joints = store_.table(solid::joint_table);
    const auto broken = solid::joint::broken.read(joints);
    const auto tets = solid::joint::tets.read(joints);
    for (size_t j = 0; j < broken.size(); ++j)
      if (broken[j] != 0) network_tet_[size_t(tets[2 * j])] = network_tet_[size_t(tets[2 * j + 1])] = 1;
  }
  const auto owned = coupling::cell::network_cell.in(store_);
  const auto& list = pairs_.broad.pairs;
  parallel_for(owned.size(), kTetGrain, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) {
      bool any = in_rock_box_[k] != 0;
      for (int64_t p = pairs_.first[k]; p < pairs_.first[k + 1] && !any; ++p)
        any = pairs_.volume[size_t(p)] > 0.0 && network_tet_[size_t(list[size_t(p)].solid)] != 0;
      owned[k] = any ? 1.0 : 0.0;
    }
  });
  for (int32_t k : pairs_.inlet_cells) owned[size_t(k)] = 0.0;
}

void SolidToFluidSystem::bind_solver_inputs() {
  const Table& ft = store_.table(fluid::tet_table);
  solver_.read_coupling_inputs(
      coupling::cell::absorption.in(ft), coupling::cell::solid_velocity.in(ft),
      settings_.dilatation ? coupling::cell::solid_dilatation.in(ft) : std::span<const double>{});
  if (settings_.fluid_continuity) {
    const auto fraction = coupling::cell::solid_fraction.in(ft);
    const auto weight = solver_.continuity_weight();
    for (size_t k = 0; k < fraction.size(); ++k) weight[k] = std::clamp(1.0 - fraction[k], 0.0, 1.0);
  }
  if (settings_.network_inlet) {
    const auto owned = coupling::cell::network_cell.in(ft);
    const auto weight = solver_.continuity_weight();
    for (size_t k = 0; k < owned.size(); ++k)
      if (owned[k] != 0.0) weight[k] = 0.0;
  }
  solver_.absorption_changed();
}

Access FluidToSolidSystem::access() const {
  using solid::col;
  Access a{
      {fluid::node::velocity.key(), coupling::cell::solid_velocity.key(),
       coupling::cell::velocity_before.key(), coupling::cell::absorption.key(), fluid::tet::nodes.key(),
       solid::tet::nodes.key()},
      {col(solid::node_table, node_force_column(NodeForceSource::fluid)), coupling::state::exchanges.key(),
       coupling::state::penalty_scale.key(), coupling::state::force.key(), coupling::state::penalty.key(),
       coupling::state::absorption.key(), coupling::state::previous_force.key(),
       coupling::state::previous_change.key(), coupling::state::growing.key()}};
  if (settings_.oscillation_lag == 2) a.writes.push_back(coupling::state::older_change.key());
  if (!pairs_.wet_faces.empty() || !settings_.volume_force) {  // sampled, or their total push reported
    a.reads.push_back(solid::node::x.key());
    a.reads.push_back(solid::face::nodes.key());
  }
  if (!pairs_.wet_faces.empty() || settings_.network_inlet) {  // the fluid's pressure at points
    a.reads.push_back(fluid::node::x.key());
    a.reads.push_back(fluid::node::pressure.key());
  }
  if (!pairs_.wet_faces.empty()) a.writes.push_back(solid::face::fluid_pressure.key());
  if (settings_.network_inlet) a.writes.push_back(fracture_flow::books::inlet_pressure.key());
  if (settings_.added_mass > 0.0) {
    a.reads.push_back(solid::node::v.key());
    a.reads.push_back(coupling::solid_node::fluid_added_mass.key());
    a.writes.push_back(coupling::solid_node::window_velocity.key());
  }
  return a;
}

void FluidToSolidSystem::run(const StepContext&) {
  exchange();
}

void FluidToSolidSystem::exchange(bool initial) {
  const Table& ft = store_.table(fluid::tet_table);
  const auto fluid_tets = fluid::tet::nodes.in(ft);
  const auto fluid_u = fluid::node::velocity.in(store_);
  const size_t nf = ft.size();
  parallel_for(nf, kTetGrain, [&](size_t b, size_t e) {
    kernels::tet_mean_vectors(fluid_u, fluid_tets, pairs_.fluid_velocity, b, e);
  });
  const auto& list = pairs_.broad.pairs;
  const size_t np = list.size();
  kernels::FluidToSolidArgs args;
  args.rho = settings_.rho;
  args.beta = initial ? 0.0 : settings_.beta;
  args.dt = settings_.dt;
  for (int d = 0; d < 3; ++d) args.body_force[d] = settings_.body_force[d];
  args.pairs = list;
  args.pair_volume = {pairs_.volume.data(), np};
  args.fluid_velocity = pairs_.fluid_velocity;
  args.fluid_velocity_old = coupling::cell::velocity_before.in(ft);
  args.target = coupling::cell::solid_velocity.in(ft);
  args.pair_weight = pairs_.pair_weight;
  args.penalty = {pairs_.penalty.data(), 3 * np};
  args.force = {pairs_.force.data(), 3 * np};
  parallel_for(np, kPairGrain, [&](size_t b, size_t e) { kernels::fluid_to_solid_pairs(args, b, e); });
  auto node_force = store_.table(solid::node_table).span<double>(node_force_column(NodeForceSource::fluid));
  if (settings_.volume_force)
    kernels::gather_to_solid_nodes(list, args.force, 3, solid::tet::nodes.in(store_), node_force);
  else
    std::fill(node_force.begin(), node_force.end(), 0.0);  // the wetted faces carry the fluid's push
  if (settings_.added_mass > 0.0) add_virtual_mass_force();
  if (!pairs_.wet_faces.empty()) sample_wetted_faces();
  if (settings_.network_inlet) sample_network_inlet();

  // Totals, in a fixed order. The fluid's own absorption force, sigma_K |K| (ubar_K - u_s,K), is summed
  // independently of the pairs: with the penalty total it checks Newton's third law.
  Table& state = store_.table(coupling::state_table);
  double force[3] = {0, 0, 0}, penalty[3] = {0, 0, 0}, absorption[3] = {0, 0, 0}, scale = 0.0;
  for (size_t p = 0; p < np; ++p)
    for (int d = 0; d < 3; ++d) {
      force[d] += args.force[3 * p + d];
      penalty[d] += args.penalty[3 * p + d];
      scale += std::abs(args.penalty[3 * p + d]);
    }
  const auto sigma = coupling::cell::absorption.in(ft);
  const auto target = coupling::cell::solid_velocity.in(ft);
  for (size_t k = 0; k < nf && !initial; ++k)
    if (sigma[k] != 0.0)
      for (int d = 0; d < 3; ++d)
        absorption[d] += sigma[k] * fluid_volume_[k] * (pairs_.fluid_velocity[3 * k + d] - target[3 * k + d]);
  if (!settings_.volume_force) wetted_face_total(force);
  watch_oscillation(force);
  coupling::state::exchanges.in(state)[0] += 1;
  coupling::state::penalty_scale.in(state)[0] = scale;
  for (int d = 0; d < 3; ++d) {
    coupling::state::force.in(state)[d] = force[d];
    coupling::state::penalty.in(state)[d] = penalty[d];
    coupling::state::absorption.in(state)[d] = absorption[d];
  }
}

void FluidToSolidSystem::set_added_mass() {
  Table& nodes = store_.table(solid::node_table);
  coupling::solid_node::fluid_added_mass.create(nodes);
  coupling::solid_node::window_velocity.create(nodes);
  const auto& list = pairs_.broad.pairs;
  std::vector<double> pair_mass(list.size());  // once, at set-up
  for (size_t p = 0; p < list.size(); ++p)
    pair_mass[p] = settings_.added_mass * settings_.rho * pairs_.volume[p];
  kernels::gather_to_solid_nodes(list, pair_mass, 1, solid::tet::nodes.in(store_),
                                 coupling::solid_node::fluid_added_mass.in(nodes));
  const auto v = solid::node::v.in(nodes);
  std::copy(v.begin(), v.end(), coupling::solid_node::window_velocity.in(nodes).begin());
}

// c_a rho_f V (a - g) with a the node's mean acceleration over the window just ended: the lagged estimate
// of the fluid's added-mass force, which the virtual mass then cancels (the solid sees m + m_a on both
// sides), less the weight the node pass gives the virtual mass.
void FluidToSolidSystem::add_virtual_mass_force() {
  Table& nodes = store_.table(solid::node_table);
  const auto extra = coupling::solid_node::fluid_added_mass.in(nodes);
  const auto v = solid::node::v.in(nodes);
  auto v_window = coupling::solid_node::window_velocity.in(nodes);
  auto force = nodes.span<double>(node_force_column(NodeForceSource::fluid));
  for (size_t i = 0; i < v.size(); ++i) {
    force[i] += extra[i / 3] * ((v[i] - v_window[i]) / settings_.dt - settings_.solid_gravity[i % 3]);
    v_window[i] = v[i];
  }
}

// The added-mass instability of a staggered exchange shows as a total fluid force whose change flips sign
// and grows; `growing` counts such fluid steps in a row (check_health stops at 4). The change is compared
// with the one `oscillation_lag` steps back: 1 in the sequential coupling, whose unstable mode flips every
// fluid step; 2 in the concurrent one, where the fluid answers a solid state two windows late (it samples
// the solid at a window's start, its force acts over the next window) and the mode flips every second step
// (measured at density ratio 0.1: 78, -257, -541, 837, 3324, -1183, -17068, ... N).
void FluidToSolidSystem::watch_oscillation(const double force[3]) {
  Table& state = store_.table(coupling::state_table);
  auto previous = coupling::state::previous_force.in(state);
  auto change = coupling::state::previous_change.in(state);
  const bool two_back = settings_.oscillation_lag == 2;
  auto older = two_back ? coupling::state::older_change.in(state) : std::span<double>{};
  const auto reference = two_back ? older : change;
  int64_t& growing = coupling::state::growing.in(state)[0];
  double delta[3], dot = 0.0, norm_old = 0.0, norm = 0.0, size = 0.0;
  for (int d = 0; d < 3; ++d) {
    delta[d] = force[d] - previous[d];
    dot += delta[d] * reference[d];
    norm_old += reference[d] * reference[d];
    norm += delta[d] * delta[d];
    size += force[d] * force[d];
  }
  const bool flips_and_grows = norm_old > 0.0 && -dot > norm_old && norm > 1e-12 * size;
  growing = flips_and_grows ? growing + 1 : 0;
  for (int d = 0; d < 3; ++d) {
    if (two_back) older[d] = change[d];
    change[d] = delta[d];
    previous[d] = force[d];
  }
}

void FluidToSolidSystem::set_wetted_faces(std::vector<int32_t> faces) {
  solid::face::fluid_pressure.create(store_);
  const size_t n = faces.size();
  pairs_.wet_faces = std::move(faces);
  pairs_.wet_points.resize(3 * n);
  pairs_.wet_pressure.resize(n);
}

// The fluid's pressure at each wetted face's current centroid, held over the next window like the force.
void FluidToSolidSystem::sample_wetted_faces() {
  const auto x = solid::node::x.in(store_);
  Table& faces = store_.table(solid::face_table);
  const auto face_nodes = solid::face::nodes.in(faces);
  auto& pts = pairs_.wet_points;
  for (size_t k = 0; k < pairs_.wet_faces.size(); ++k) {
    const size_t f = static_cast<size_t>(pairs_.wet_faces[k]);
    for (int d = 0; d < 3; ++d) {
      double c = 0.0;
      for (int a = 0; a < 3; ++a) c += x[3 * static_cast<size_t>(face_nodes[3 * f + a]) + d];
      pts[3 * k + d] = c / 3.0;
    }
  }
  kernels::coupling_broad_phase({pts, pts, pairs_.fluid_lo, pairs_.fluid_hi, 0.0}, pairs_.wet_broad);
  const Table& ft = store_.table(fluid::tet_table);
  pairs_.wet_outside = kernels::interpolate_p1_at_points(fluid::node::x.in(store_), fluid::tet::nodes.in(ft),
                                                         fluid::node::pressure.in(store_), pts,
                                                         pairs_.wet_broad.pairs, pairs_.wet_pressure);
  auto p = solid::face::fluid_pressure.in(faces);
  for (size_t k = 0; k < pairs_.wet_faces.size(); ++k)
    p[static_cast<size_t>(pairs_.wet_faces[k])] = pairs_.wet_pressure[k];
}

// The fluid's pressure at the network inlet, the cracks' well pressure over the next window, in the cells
// the sink of this window's fluid step used (SolidToFluidSystem::network_sink, on the same mesh).
void FluidToSolidSystem::sample_network_inlet() {
  const Table& nodes = store_.table(fluid::node_table);
  pairs_.inlet_pressure = inlet_pressure(settings_, fluid::node::x.in(nodes), fluid::tet::nodes.in(store_),
                                         fluid::node::pressure.in(nodes), pairs_);
  fracture_flow::books::inlet_pressure.in(store_)[0] = pairs_.inlet_pressure;
}

// The wetted faces' total push, sum_f -p_f n_f A_f (kernels::face_area_vector), in face order.
void FluidToSolidSystem::wetted_face_total(double force[3]) const {
  const auto x = solid::node::x.in(store_);
  const Table& faces = store_.table(solid::face_table);
  const auto nodes = solid::face::nodes.in(faces);
  for (int d = 0; d < 3; ++d) force[d] = 0.0;
  for (size_t k = 0; k < pairs_.wet_faces.size(); ++k) {
    double na[3];
    kernels::face_area_vector(x, nodes, static_cast<size_t>(pairs_.wet_faces[k]), na);
    for (int d = 0; d < 3; ++d) force[d] -= pairs_.wet_pressure[k] * na[d];
  }
}

}  // namespace rift
