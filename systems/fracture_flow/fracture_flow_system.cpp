#include "systems/fracture_flow/fracture_flow_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/schedule/parallel.hpp"
#include "kernels/crack_pressure_closure.hpp"
#include "systems/fracture_flow/fracture_flow_tables.hpp"
#include "systems/node_force_route.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

using fracture_flow::books_table;
using fracture_flow::vertex_table;

FractureFlowSystem::FractureFlowSystem(Store& store, const FractureFlowSpec& spec, TimeFunction mass_damping,
                                       std::vector<uint8_t> vent_vertex, WellWall wall)
    : store_(store),
      spec_(spec),
      mass_damping_(std::move(mass_damping)),
      wall_(std::move(wall)),
      flow_(spec.eos, spec.viscosity, spec.lag_pressure, spec.solver) {
  // One row per mesh vertex that a joint touches, in vertex order; with a borehole well, the wall's
  // vertices all share one more row, the well's (mesh_vertex -1).
  const auto joint_nodes = solid::joint::nodes.read(store_);
  const auto node_vertex = solid::node::vertex.read(store_);
  std::vector<int32_t> vertices;
  for (int32_t n : joint_nodes)
    if (!well_is_wall() || !wall_.on_wall[size_t(node_vertex[size_t(n)])])
      vertices.push_back(node_vertex[size_t(n)]);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  row_of_mesh_vertex_.assign(vent_vertex.size(), -1);
  for (size_t r = 0; r < vertices.size(); ++r) row_of_mesh_vertex_[size_t(vertices[r])] = int32_t(r);
  if (well_is_wall()) {
    well_row_ = vertices.size();
    for (size_t v = 0; v < wall_.on_wall.size(); ++v)
      if (wall_.on_wall[v]) row_of_mesh_vertex_[v] = int32_t(well_row_);
  }
  Table& rows = store_.add_table(vertex_table);
  fracture_flow::vertex::mesh_vertex.create(rows).indexes(
      well_is_wall() ? IndexTarget::list_of(vent_vertex.size()).or_none()
                     : IndexTarget::list_of(vent_vertex.size()));
  fracture_flow::vertex::pressure.create(rows);
  fracture_flow::vertex::mass.create(rows);
  fracture_flow::vertex::role.create(rows);
  fracture_flow::vertex::wetting_time.create(rows);
  fracture_flow::vertex::exchanged.create(rows);
  fracture_flow::vertex::volume.create(rows);
  rows.resize(vertices.size() + (well_is_wall() ? 1 : 0));
  std::copy(vertices.begin(), vertices.end(), fracture_flow::vertex::mesh_vertex.in(rows).begin());
  if (well_is_wall()) fracture_flow::vertex::mesh_vertex.in(rows)[well_row_] = -1;
  auto pressure = fracture_flow::vertex::pressure.in(rows);
  std::fill(pressure.begin(), pressure.end(), spec_.lag_pressure);
  auto wetting = fracture_flow::vertex::wetting_time.in(rows);
  std::fill(wetting.begin(), wetting.end(), -1.0);
  vent_row_.assign(rows.size(), 0);
  for (size_t r = 0; r < vertices.size(); ++r) vent_row_[r] = vent_vertex[size_t(vertices[r])];
  Table& books = store_.add_table(books_table);
  namespace fb = fracture_flow::books;
  for (const auto& c : {fb::injected, fb::vented, fb::leaked, fb::dissipation, fb::pump_work, fb::fluid_work,
                        fb::initial_mass})
    c.create(books);
  // The well's pressure when the surrounding fluid sets it (FractureFlowSpec::pressure_from_fluid): written
  // by the fluid-solid coupling after each fluid step, the fluid's initial pressure until then.
  if (spec_.pressure_from_fluid) fracture_flow::books::inlet_pressure.create(books);
  books.resize(1);
  if (spec_.pressure_from_fluid) fracture_flow::books::inlet_pressure.in(books)[0] = spec_.initial_pressure;
  Table& joined = store_.add_table(fracture_flow::joint_table);
  fracture_flow::joint::joined.create(joined);
  joined.resize(store_.table(solid::joint_table).size());
  auto order = fracture_flow::joint::joined.in(joined);
  std::fill(order.begin(), order.end(), -1);
  local_of_row_.assign(rows.size(), -1);
  entry_of_node_.assign(store_.table(solid::node_table).size(), -1);
  add_well_wall();
  sync_network();
  if (joints_.empty()) network_changed();  // a borehole well alone, before any crack
  initial_fill();
}

// The borehole's well is network vertex 0 from the start, and its wall nodes are the first entries, so
// that the numbering is the same after a restart.
void FractureFlowSystem::add_well_wall() {
  if (!well_is_wall()) return;
  local_of_row_[well_row_] = 0;
  row_of_local_.push_back(int32_t(well_row_));
  wall_entry_.clear();
  wall_x0_.clear();
  wall_entries_ = 0;
  const auto x0 = solid::node::x0.read(store_);
  for (int32_t node : wall_.face_nodes) {
    if (entry_of_node_[size_t(node)] < 0) {
      entry_of_node_[size_t(node)] = int32_t(node_.size());
      node_.push_back(node);
      node_vertex_.push_back(0);
      felt_.push_back(0.0);
      for (size_t d = 0; d < 3; ++d) wall_x0_.push_back(x0[3 * size_t(node) + d]);
      ++wall_entries_;
    }
    wall_entry_.push_back(entry_of_node_[size_t(node)]);
  }
}

Access FractureFlowSystem::access() const {
  using solid::col;
  const char* N = solid::node_table;
  std::vector<std::string> reads{solid::node::inv_mass.key(), solid::node::free.key(),
                                 solid::node::vertex.key(), solid::joint::nodes.key(),
                                 solid::event::joint.key()};
  if (spec_.wet_damage < 1.0) reads.push_back(solid::joint::d_max.key());
  if (well_is_wall()) reads.push_back(solid::node::x0.key());
  if (spec_.pressure_from_fluid) reads.push_back(fracture_flow::books::inlet_pressure.key());
  reads.push_back(fracture_flow::books::initial_mass.key());
  std::vector<std::string> writes{solid::node::x.key(), solid::node::v.key(),
                                  col(N, node_force_column(NodeForceSource::crack)),
                                  solid::energy::external_work.key()};
  namespace fv = fracture_flow::vertex;
  namespace fb = fracture_flow::books;
  writes.insert(writes.end(), {fv::pressure.key(), fv::mass.key(), fv::role.key(), fv::wetting_time.key(),
                               fv::exchanged.key(), fv::volume.key(), fracture_flow::joint::joined.key(),
                               fb::injected.key(), fb::vented.key(), fb::leaked.key(), fb::dissipation.key(),
                               fb::pump_work.key(), fb::fluid_work.key()});
  return {reads, writes};
}

// Joints join the network in a fixed order: each step the fracture log's new rows (initial cracks first),
// then, with wet_damage below 1, the joints whose damage reached it, by joint index. The order is
// recorded (fracture_flow_joint.joined), so the local numbering, and with it every sum, is the same on any
// thread count and after a restart.
void FractureFlowSystem::sync_network() {
  auto joined = fracture_flow::joint::joined.in(store_);
  const size_t before = joints_.size();
  const auto events = solid::event::joint.read(store_);
  for (size_t k = events_seen_; k < events.size(); ++k)
    if (joined[size_t(events[k])] < 0) join(size_t(events[k]));
  events_seen_ = events.size();
  if (spec_.wet_damage < 1.0) {
    const Table& joints = store_.table(solid::joint_table);
    const auto d_max = solid::joint::d_max.read(joints);
    const size_t points = d_max.size() / std::max<size_t>(joints.size(), 1);
    for (size_t j = 0; j < joints.size(); ++j) {
      if (joined[j] >= 0) continue;
      const double* d = &d_max[points * j];
      if (*std::max_element(d, d + points) >= spec_.wet_damage) join(j);
    }
  }
  if (joints_.size() != before) network_changed();
}

void FractureFlowSystem::join(size_t j) {
  auto joined = fracture_flow::joint::joined.in(store_);
  joined[j] = int64_t(joints_.size());
  add_triangle(j);
}

void FractureFlowSystem::add_triangle(size_t j) {
  const auto joint_nodes = solid::joint::nodes.read(store_);
  const auto node_vertex = solid::node::vertex.read(store_);
  joints_.push_back(int32_t(j));
  triangle_nodes_.insert(triangle_nodes_.end(), &joint_nodes[6 * j], &joint_nodes[6 * j] + 6);
  for (int c = 0; c < 3; ++c) {
    const size_t row =
        size_t(row_of_mesh_vertex_[size_t(node_vertex[size_t(joint_nodes[6 * j + size_t(c)])])]);
    if (local_of_row_[row] < 0) {
      local_of_row_[row] = int32_t(row_of_local_.size());
      row_of_local_.push_back(int32_t(row));
    }
    triangles_.push_back(local_of_row_[row]);
  }
  for (int c = 0; c < 6; ++c) {
    const int32_t node = joint_nodes[6 * j + size_t(c)];
    if (entry_of_node_[size_t(node)] < 0) {
      entry_of_node_[size_t(node)] = int32_t(node_.size());
      node_.push_back(node);
      const size_t row = size_t(row_of_mesh_vertex_[size_t(node_vertex[size_t(node)])]);
      node_vertex_.push_back(local_of_row_[row]);
      felt_.push_back(0.0);  // a new corner has felt no pressure yet
    }
    corner_entry_.push_back(entry_of_node_[size_t(node)]);
  }
}

// The flow's pattern and the per-step arrays follow the network's size.
void FractureFlowSystem::network_changed() {
  const size_t nv = row_of_local_.size(), nt = joints_.size(), ne = node_.size();
  flow_.set_network(triangles_, nv);
  for (auto* v : {&volume_, &floor_volume_, &compliance_, &compliance_open_, &applied_, &source_, &fixed_,
                  &pressure_, &previous_pressure_, &mass_, &wetting_, &exchanged_, &vertex_area_})
    v->assign(nv, 0.0);
  vertex_x_.assign(3 * nv, 0.0);
  role_.assign(nv, 0);
  tri_x_.assign(9 * nt, 0.0);
  aperture_.assign(3 * nt, 0.0);
  opening_.assign(3 * nt, 0.0);
  normal_.assign(3 * nt, 0.0);
  area_.assign(nt, 0.0);
  area_vector_.assign(3 * ne, 0.0);
  open_area_vector_.assign(3 * ne, 0.0);
  now_.assign(ne, 0.0);
  vertex_corners_.build(triangles_, nv);
  entry_corners_.build(corner_entry_, ne);
  vertex_entries_.build(node_vertex_, nv);
  const Table& nodes = store_.table(solid::node_table);
  const auto inv_mass = solid::node::inv_mass.read(nodes);
  const auto free = solid::node::free.read(nodes);
  for (size_t i = entry_inv_mass_.size(); i < ne; ++i) {
    const size_t n = size_t(node_[i]);
    entry_inv_mass_.push_back(inv_mass[n]);
    entry_free_.insert(entry_free_.end(), &free[3 * n], &free[3 * n] + 3);
  }
}

// At t = 0 the initial cracks hold fluid at the initial pressure, and the well is the crack vertex nearest
// the injection point.
void FractureFlowSystem::initial_fill() {
  if (well_is_wall()) {
    geometry();
  } else {
    locate_well();
  }
  fill_initial_cracks();
}

// The well is the crack vertex nearest the injection point, within an element of it.
void FractureFlowSystem::locate_well() {
  if (row_of_local_.empty())
    throw Error(
        "fracture_flow: no crack to inject into at t = 0; add a starter crack "
        "(solid.fracture.initial_cracks) "
        "through fracture_flow.injection.point");
  geometry();
  size_t best = 0;
  double best_d2 = INFINITY;
  for (size_t v = 0; v < row_of_local_.size(); ++v) {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) d2 += std::pow(vertex_x_[3 * v + size_t(d)] - spec_.point[size_t(d)], 2);
    if (d2 < best_d2) best_d2 = d2, best = v;
  }
  // Within an element: no farther than the longest edge of a crack triangle at that vertex.
  double reach = 0.0;
  for (size_t t = 0; t < joints_.size(); ++t)
    for (int c = 0; c < 3; ++c)
      if (size_t(triangles_[3 * t + size_t(c)]) == best)
        for (int e = 0; e < 3; ++e) {
          double d2 = 0.0;
          for (int d = 0; d < 3; ++d)
            d2 += std::pow(tri_x_[9 * t + 3 * size_t(e) + size_t(d)] -
                               tri_x_[9 * t + 3 * size_t((e + 1) % 3) + size_t(d)],
                           2);
          reach = std::max(reach, std::sqrt(d2));
        }
  if (std::sqrt(best_d2) > reach)
    throw Error(fmt::format(
        "fracture_flow.injection.point: [{:.6g}, {:.6g}, {:.6g}] is {:.4g} m from the nearest crack vertex "
        "([{:.6g}, {:.6g}, {:.6g}]), farther than an element ({:.4g} m); put the well on a starter crack",
        spec_.point[0], spec_.point[1], spec_.point[2], std::sqrt(best_d2), vertex_x_[3 * best],
        vertex_x_[3 * best + 1], vertex_x_[3 * best + 2], reach));
  well_row_ = size_t(row_of_local_[best]);
}

void FractureFlowSystem::fill_initial_cracks() {
  Table& rows = store_.table(vertex_table);
  auto pressure = fracture_flow::vertex::pressure.in(rows);
  auto mass = fracture_flow::vertex::mass.in(rows);
  auto role = fracture_flow::vertex::role.in(rows);
  auto wetting = fracture_flow::vertex::wetting_time.in(rows);
  auto volume = fracture_flow::vertex::volume.in(rows);
  const double p0 = spec_.initial_pressure;
  double total = 0.0;
  for (size_t v = 0; v < row_of_local_.size(); ++v) {
    const size_t r = size_t(row_of_local_[v]);
    const double vol = volume_[v] + (r == well_row_ ? spec_.well_volume : 0.0);
    pressure[r] = p0;
    mass[r] = spec_.eos.density(p0) * vol;
    role[r] = uint8_t(FlowRole::wet);
    wetting[r] = 0.0;
    volume[r] = vol;
    total += mass[r];
  }
  fracture_flow::books::initial_mass.in(store_)[0] = total;
  // The faces carry the initial pressure from the first step on.
  auto force = store_.table(solid::node_table).span<double>(node_force_column(NodeForceSource::crack));
  for (size_t i = 0; i < node_.size(); ++i) {
    felt_[i] = p0;
    for (int d = 0; d < 3; ++d)
      force[3 * size_t(node_[i]) + size_t(d)] = p0 * area_vector_[3 * i + size_t(d)];
  }
}

void FractureFlowSystem::restored() {
  joints_.clear();
  triangle_nodes_.clear();
  triangles_.clear();
  node_.clear();
  node_vertex_.clear();
  corner_entry_.clear();
  felt_.clear();
  entry_inv_mass_.clear();
  entry_free_.clear();
  row_of_local_.clear();
  std::fill(local_of_row_.begin(), local_of_row_.end(), -1);
  std::fill(entry_of_node_.begin(), entry_of_node_.end(), -1);
  add_well_wall();
  // The checkpoint's network, in the order it was built.
  const auto joined = fracture_flow::joint::joined.read(store_);
  std::vector<std::pair<int64_t, size_t>> order;
  for (size_t j = 0; j < joined.size(); ++j)
    if (joined[j] >= 0) order.emplace_back(joined[j], j);
  std::sort(order.begin(), order.end());
  for (const auto& [k, j] : order) add_triangle(j);
  events_seen_ = store_.table(solid::event_table).size();
  network_changed();
  // Every corner in the checkpoint's network had felt its vertex's pressure (the step before wrote it).
  const auto pressure = fracture_flow::vertex::pressure.read(store_);
  for (size_t i = 0; i < node_.size(); ++i)
    felt_[i] = pressure[size_t(row_of_local_[size_t(node_vertex_[i])])];
  geometry();
}

void FractureFlowSystem::run(const StepContext& ctx) {
  problem_.clear();
  const size_t old_triangles = joints_.size();
  sync_network();
  geometry();
  // The crack space that joined with the new triangles was opened by the rock, not by the fluid: it is
  // not part of the fluid's work.
  joining_.assign(row_of_local_.size(), 0.0);
  for (size_t t = old_triangles; t < joints_.size(); ++t)
    for (size_t c = 0; c < 3; ++c)
      joining_[size_t(triangles_[3 * t + c])] += area_[t] * aperture_[3 * t + c] / 3.0;
  Table& rows = store_.table(vertex_table);
  auto pressure = fracture_flow::vertex::pressure.in(rows);
  auto mass = fracture_flow::vertex::mass.in(rows);
  auto role = fracture_flow::vertex::role.in(rows);
  auto wetting = fracture_flow::vertex::wetting_time.in(rows);
  auto exchanged = fracture_flow::vertex::exchanged.in(rows);
  auto volume = fracture_flow::vertex::volume.in(rows);
  const size_t nv = row_of_local_.size();
  const size_t w = size_t(local_of_row_[well_row_]);
  for (size_t v = 0; v < nv; ++v) {
    const size_t r = size_t(row_of_local_[v]);
    pressure_[v] = pressure[r];
    mass_[v] = mass[r];
    role_[v] = role[r];
    wetting_[v] = wetting[r];
    exchanged_[v] = 0.0;
    // A vent holds its pressure once the fluid has reached it (where a wet crack meets an outer face):
    // before that it is a dry part of the crack like any other, and nothing enters from outside.
    const bool reached = FlowRole(role[r]) == FlowRole::wet || FlowRole(role[r]) == FlowRole::fixed;
    if (spec_.vent_pressure && vent_row_[r] && r != well_row_ && reached) {
      role_[v] = uint8_t(FlowRole::fixed);
      fixed_[v] = *spec_.vent_pressure;
    }
  }
  const double t_end = ctx.time + ctx.dt;
  if (spec_.pressure) {
    role_[w] = uint8_t(FlowRole::fixed);
    fixed_[w] = (*spec_.pressure)(t_end);
  } else if (spec_.pressure_from_fluid) {
    role_[w] = uint8_t(FlowRole::fixed);
    fixed_[w] = fracture_flow::books::inlet_pressure.in(store_)[0];
  }

  // The closure's compliance, and the pressure the predicted volumes already felt (the compliance-weighted
  // mean of the corners': a corner that joined the network this step felt none).
  const double damping_factor = 1.0 / (1.0 + 0.5 * mass_damping_(ctx.time) * ctx.dt);
  const kernels::CrackClosureNodes closure{node_, node_vertex_, area_vector_, entry_inv_mass_, entry_free_};
  kernels::CrackClosureNodes open_closure = closure;
  open_closure.open_area_vector = open_area_vector_;
  closure_compliance(closure, open_closure, ctx.dt * ctx.dt * damping_factor);
  for (size_t v = 0; v < nv; ++v)
    applied_[v] = compliance_[v] > 0.0 ? applied_[v] / compliance_[v] : pressure_[v];
  // The well's own storage: V_w(p) = well_volume + well_compliance (p - initial_pressure).
  volume_[w] += spec_.well_volume + spec_.well_compliance * (applied_[w] - spec_.initial_pressure);
  floor_volume_[w] += spec_.well_volume;
  compliance_[w] += spec_.well_compliance;
  compliance_open_[w] += spec_.well_compliance;

  Table& books = store_.table(books_table);
  double injected = 0.0, leaked = 0.0;
  if (spec_.rate) {
    injected = ctx.dt * spec_.eos.density0 * (*spec_.rate)(ctx.time + 0.5 * ctx.dt);
    mass_[w] += injected;
  }
  if (spec_.leak_off > 0.0 || spec_.spurt > 0.0)
    for (size_t v = 0; v < nv; ++v) {
      if (wetting_[v] < 0.0 || FlowRole(role_[v]) == FlowRole::fixed) continue;
      // Carter: each of the two faces loses C_L / sqrt(t - t_wet) per unit area, and the spurt once, in
      // the step after it wets; never more than the vertex holds.
      const double faces = 2.0 * vertex_area_[v];
      double lost = faces * 2.0 * spec_.leak_off *
                    (std::sqrt(t_end - wetting_[v]) - std::sqrt(std::max(ctx.time - wetting_[v], 0.0)));
      if (wetting_[v] > ctx.time - ctx.dt && wetting_[v] <= ctx.time) lost += faces * spec_.spurt;
      const double dm = std::min(spec_.eos.density(pressure_[v]) * lost, mass_[v]);
      mass_[v] -= dm;
      leaked += dm;
    }

  std::fill(source_.begin(), source_.end(), 0.0);
  const int64_t interval = spec_.interval;
  const bool solve = runs_at(interval, ctx);
  const NetworkFlowStepInput in{solve ? double(interval) * ctx.dt : ctx.dt,
                                t_end,
                                tri_x_,
                                aperture_,
                                volume_,
                                compliance_,
                                applied_,
                                source_,
                                fixed_,
                                compliance_open_,
                                floor_volume_};
  NetworkFlowState state{pressure_, mass_, role_, wetting_, exchanged_};
  NetworkFlowBooks step_books;
  previous_pressure_.assign(pressure_.begin(), pressure_.end());
  std::string problem = solve ? flow_.step(in, state, step_books) : flow_.local_step(in, state);
  if (!problem.empty()) {
    problem_ = fmt::format("fracture_flow at t = {:.6g} s (step {}): {}", t_end, ctx.step, problem);
    return;
  }

  // The corners move for the pressure change their walls take within the step (the new pressure, or for
  // a vertex closed onto its floor only as far as the floor) and carry the new pressure into the next
  // node pass.
  const auto wall_pressure = flow_.wall_pressure();
  for (size_t i = 0; i < node_.size(); ++i) now_[i] = wall_pressure[size_t(node_vertex_[i])];
  Table& solid_nodes = store_.table(solid::node_table);
  const auto x = solid::node::x.in(solid_nodes), v = solid::node::v.in(solid_nodes);
  auto force = solid_nodes.span<double>(node_force_column(NodeForceSource::crack));
  const double correction_work =
      parallel_sum(node_.size(), kEntryGrain, work_blocks_, [&](size_t b, size_t e) {
        const double work =
            kernels::apply_closure_block(closure, ctx.dt, damping_factor, felt_, now_, x, v, b, e);
        for (size_t i = b; i < e; ++i) {
          if (i + kPrefetchAhead < e) __builtin_prefetch(&force[3 * size_t(node_[i + kPrefetchAhead])], 1);
          felt_[i] = pressure_[size_t(node_vertex_[i])];
          for (size_t d = 0; d < 3; ++d) force[3 * size_t(node_[i]) + d] = felt_[i] * area_vector_[3 * i + d];
        }
        return work;
      });
  solid::energy::external_work.in(store_)[0] += correction_work;

  double vented = 0.0, fluid_work = 0.0, total = 0.0;
  for (size_t v = 0; v < nv; ++v) {
    const size_t r = size_t(row_of_local_[v]);
    const double new_volume = flow_.volume_used()[v];
    fluid_work += 0.5 * (previous_pressure_[v] + pressure_[v]) * (new_volume - volume[r] - joining_[v]);
    if (v == w)
      injected += exchanged_[v];
    else
      vented -= exchanged_[v];
    pressure[r] = pressure_[v];
    mass[r] = mass_[v];
    role[r] = role_[v];
    wetting[r] = wetting_[v];
    exchanged[r] += exchanged_[v];
    volume[r] = new_volume;
    total += mass_[v];
  }
  const double well_pressure = 0.5 * (previous_pressure_[w] + pressure_[w]);
  fracture_flow::books::injected.in(books)[0] += injected;
  fracture_flow::books::vented.in(books)[0] += vented;
  fracture_flow::books::leaked.in(books)[0] += leaked;
  fracture_flow::books::dissipation.in(books)[0] += step_books.dissipation;
  fracture_flow::books::fluid_work.in(books)[0] += fluid_work;
  // The pump takes the injected mass from the reference state into the well: it compresses it to the
  // well's pressure (e(p) per unit mass, the compression energy it brings in) and displaces it there,
  // where it takes the volume m / rho(p).
  fracture_flow::books::pump_work.in(books)[0] +=
      injected *
      (well_pressure / spec_.eos.density(well_pressure) + specific_compression_energy(well_pressure));
  // The mass books: what the network holds is what it started with, plus what came in, less what left.
  const double in_total = fracture_flow::books::injected.in(books)[0],
               initial = fracture_flow::books::initial_mass.in(books)[0];
  const double expected = initial + in_total - fracture_flow::books::vented.in(books)[0] -
                          fracture_flow::books::leaked.in(books)[0];
  // 1e-12 of the mass involved, or, over a long run, the rounding of the additions to a vertex's mass (one
  // part in 2^52 per step: a large well's mass takes each step's small injection rounded to its own ulp).
  const double scale = std::max({std::abs(total), std::abs(initial), std::abs(in_total)});
  const double allowed = std::max(1e-12, double(ctx.step + 1) * 0x1p-52);
  if (std::abs(total - expected) > allowed * scale)
    problem_ = fmt::format(
        "fracture_flow at t = {:.6g} s (step {}): the fluid's mass books do not close: the network holds "
        "{:.12g} kg "
        "but started with {:.12g}, took in {:.12g}, vented {:.12g} and leaked {:.12g} kg (relative error "
        "{:.3g}, allowed {:.3g}). This is a defect of the flow step; please report it with the scene.",
        t_end, ctx.step, total, initial, in_total, fracture_flow::books::vented.in(books)[0],
        fracture_flow::books::leaked.in(books)[0], std::abs(total - expected) / scale, allowed);
}

// The work that compressed a unit mass from rho0 to rho(p), the integral of p d(1 / rho) along the
// equation of state: (K_f / rho0) [ln(1 + x) + 1 / (1 + x) - 1] + p0 x / (rho0 (1 + x)), x = (p - p0) / K_f.
double FractureFlowSystem::specific_compression_energy(double p) const {
  const double x = (p - spec_.eos.pressure0) / spec_.eos.bulk_modulus;
  return (spec_.eos.bulk_modulus * (std::log1p(x) + 1.0 / (1.0 + x) - 1.0) +
          spec_.eos.pressure0 * x / (1.0 + x)) /
         spec_.eos.density0;
}

double FractureFlowSystem::total_mass() const {
  const auto mass = fracture_flow::vertex::mass.read(store_);
  double total = 0.0;
  for (int32_t r : row_of_local_) total += mass[size_t(r)];
  return total;
}

FractureFlowSystem::Measures FractureFlowSystem::measure() const {
  Measures m;
  const Table& rows = store_.table(vertex_table);
  const auto pressure = fracture_flow::vertex::pressure.read(rows);
  const auto mass = fracture_flow::vertex::mass.read(rows);
  const auto role = fracture_flow::vertex::role.read(rows);
  const auto volume = fracture_flow::vertex::volume.read(rows);
  m.well_pressure = pressure[well_row_];
  const size_t w = size_t(local_of_row_[well_row_]);
  for (size_t v = 0; v < row_of_local_.size(); ++v) {
    const size_t r = size_t(row_of_local_[v]);
    m.crack_volume += volume[r];
    m.fluid_volume += mass[r] / spec_.eos.density0;
    m.compression_energy += mass[r] * specific_compression_energy(pressure[r]);
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d)
      d2 += std::pow(vertex_x_[3 * v + size_t(d)] - vertex_x_[3 * w + size_t(d)], 2);
    m.crack_extent = std::max(m.crack_extent, std::sqrt(d2));
    // The front is the farthest vertex the fluid has reached, full or still filling: in a crack that
    // keeps opening ahead of the fluid, the vertices at the front are filling, never full.
    if (FlowRole(role[r]) == FlowRole::wet || FlowRole(role[r]) == FlowRole::filling)
      m.front_extent = std::max(m.front_extent, std::sqrt(d2));
    if (FlowRole(role[r]) == FlowRole::wet) {
      ++m.wet_vertices;
      m.wet_area += vertex_area_[v];
    }
  }
  // The crack's own volume: without the well's storage (and a borehole's expansion).
  m.crack_volume -= spec_.well_volume + spec_.well_compliance * (m.well_pressure - spec_.initial_pressure);
  if (well_is_wall()) m.crack_volume -= hole_change_;
  for (double a : area_) m.crack_area += a;
  m.triangles = joints_.size();
  return m;
}

void FractureFlowSystem::network_geometry(std::vector<double>& points, std::vector<int32_t>& triangles,
                                          std::vector<int32_t>& rows, std::vector<double>& aperture) const {
  points = vertex_x_;
  triangles = triangles_;
  rows = row_of_local_;
  aperture.assign(row_of_local_.size(), 0.0);
  for (size_t t = 0; t < area_.size(); ++t)
    for (size_t c = 0; c < 3; ++c)
      aperture[size_t(triangles_[3 * t + c])] += area_[t] / 3.0 * aperture_[3 * t + c];
  for (size_t v = 0; v < aperture.size(); ++v)
    if (vertex_area_[v] > 0.0) aperture[v] /= vertex_area_[v];
  if (!well_is_wall()) return;
  // A borehole's well gathers every wall point into one vertex placed at the injection point: drawn there,
  // the cracks would reach into the hole. Each crack corner on the wall is drawn where it is instead, with
  // the well's row (its pressure) and its own aperture.
  for (size_t k = 0; k < triangles.size(); ++k) {
    if (triangles[k] != 0) continue;
    triangles[k] = int32_t(rows.size());
    rows.push_back(int32_t(well_row_));
    aperture.push_back(aperture_[k]);
    for (size_t d = 0; d < 3; ++d) points.push_back(tri_x_[3 * k + d]);
  }
}

}  // namespace rift
