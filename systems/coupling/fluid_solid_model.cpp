#include "systems/coupling/fluid_solid_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/scene/output_fields.hpp"
#include "systems/coupling/fluid_solid_tables.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/fracture_flow/fracture_flow_tables.hpp"
#include "systems/node_force_route.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

int64_t FluidSolidModel::automatic_substeps(double fluid_dt, double solid_stable_dt, double safety) {
  const double n = fluid_dt / (safety * solid_stable_dt);
  return std::max<int64_t>(1, static_cast<int64_t>(std::ceil(n * (1.0 - 1e-12))));
}

FluidSolidModel::FluidSolidModel(Store& store, SolidModel& solid, FluidModel& fluid,
                                 const FluidSolidSpec& spec, std::unique_ptr<FluidMeshAdapter> adapter,
                                 std::vector<int32_t> well_wall_tets)
    : store_(store), fluid_(fluid), spec_(spec), adapter_(std::move(adapter)) {
  settings_.substeps = fluid.substeps();
  settings_.beta = spec.relaxation_time > 0.0 ? fluid.spec().dt / spec.relaxation_time : spec.beta;
  settings_.rho = fluid.spec().density;
  settings_.dt = fluid.spec().dt;
  settings_.body_force = fluid.spec().body_force;
  settings_.added_mass = spec.added_mass;
  settings_.dilatation = spec.dilatation;
  settings_.fluid_continuity = spec.continuity == FluidSolidSpec::Continuity::fluid;
  settings_.network_inlet = spec.network_inlet;
  settings_.network_inlet_extent = spec.network_inlet_extent;
  settings_.volume_force = spec.force == FluidSolidSpec::Force::volume;
  settings_.solid_gravity = solid.spec().gravity;
  if (spec.coupling == FluidSolidSpec::Coupling::concurrent) settings_.oscillation_lag = 2;
  Table& state = store_.add_table(coupling::state_table);
  namespace cs = coupling::state;
  for (const auto& c : {cs::exchanges, cs::pairs, cs::cut_cells}) c.create(state);
  for (const auto& c : {cs::solid_volume, cs::penalty_scale}) c.create(state);
  for (const auto& c : {cs::force, cs::penalty, cs::absorption, cs::previous_force, cs::previous_change})
    c.create(state);
  coupling::state::growing.create(state);
  // The network inlet's books: the network's intake (its well's injected mass) at the last exchange, and
  // the mass the fluid has given up through the sink so far.
  if (spec.network_inlet)
    for (const auto& c : {cs::inlet_injected, cs::inlet_sink_mass}) c.create(state);
  // Concurrent only (so the sequential coupling's state, and its hash, are unchanged): 1 while the store's
  // fluid state is already the window's end, a checkpoint having joined the fluid step mid-window. A
  // restart from there must not take that step again.
  if (spec.coupling == FluidSolidSpec::Coupling::concurrent) {
    coupling::state::fluid_ahead.create(state);
    coupling::state::older_change.create(state);  // the oscillation watch's change two fluid steps back
  }
  state.resize(1);
  solid.accept_fluid_forces();
  to_fluid_ = std::make_unique<SolidToFluidSystem>(store_, fluid.solver(), settings_, pairs_);
  if (spec.network_inlet) to_fluid_->set_network_wall(well_wall_tets);
  to_solid_ = std::make_unique<FluidToSolidSystem>(store_, settings_, pairs_, fluid.solver().volumes());
  if (spec.coupling == FluidSolidSpec::Coupling::concurrent) {
    fluid_step_ = &fluid.step();
    concurrent_ = std::make_unique<ConcurrentFluidStep>(*fluid_step_);
    // The solid's positions at the last exchange: its pairs serve the window's end, so a restart inside
    // the window finds them again from these (SolidToFluidSystem::rebuild_pairs).
    coupling::solid_node::x_at_exchange.create(store_);
  }
  for (double v : solid::tet::volume0.in(store_)) solid_volume_ += v;
  // The exchange at t = 0: the fluid's first step sees the solid, and the first window already feels the
  // fluid's body force (buoyancy); the absorption's reaction follows from the first fluid step on.
  std::vector<int32_t> wetted;
  const auto& loads = solid.load_conditions();
  const auto face_load = solid::face::load.in(store_);
  for (size_t f = 0; f < face_load.size(); ++f)
    if (loads[static_cast<size_t>(face_load[f])].kind == SolidBoundarySpec::Kind::fluid_pressure)
      wetted.push_back(static_cast<int32_t>(f));
  if (!wetted.empty()) to_solid_->set_wetted_faces(std::move(wetted));
  to_fluid_->exchange();
  if (concurrent_) keep_exchange_positions();
  if (spec.added_mass > 0.0) {
    to_solid_->set_added_mass();
    solid.add_node_mass(coupling::solid_node::fluid_added_mass.in(store_));
  }
  to_solid_->exchange(/*initial=*/true);
  coupling::state::growing.in(store_)[0] = 0;
  coupling::state::exchanges.in(store_)[0] = 0;
}

FluidSolidModel::~FluidSolidModel() = default;

void FluidSolidModel::restored(const StepContext&) {
  if (adapter_) fluid_mesh_changed();  // the fluid model rebuilt its solver on the checkpoint's mesh
  to_fluid_->bind_solver_inputs();
  if (concurrent_) to_fluid_->rebuild_pairs(coupling::solid_node::x_at_exchange.in(store_));
}

void FluidSolidModel::keep_exchange_positions() {
  Table& nodes = store_.table(solid::node_table);
  const auto x = solid::node::x.in(nodes);
  std::copy(x.begin(), x.end(), coupling::solid_node::x_at_exchange.in(nodes).begin());
}

// The window of solid steps [t_n, t_n+1) starts with the launch of the fluid step t_n -> t_n+1, from what
// the exchange at t_n (the window before's, or the constructor's at t = 0) gave the solver.
void FluidSolidModel::launch(const StepContext& at) {
  concurrent_->launch(at.time);
}

namespace {
template <class F>
void timed(SystemTiming& t, F&& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++t.calls;
}
}  // namespace

// At the window's end t_n+1, once the fluid step is joined: its force goes to the solid for the next
// window, as in the sequential coupling but for the solid's time the fluid saw.
void FluidSolidModel::exchange_fluid_to_solid(const StepContext&) {
  coupling::state::fluid_ahead.in(store_)[0] = 0;
  timed(to_solid_time_, [&] { to_solid_->exchange(); });
}

// The solid at t_n+1 goes to the fluid for its next step. The concurrent coupling keeps the positions the
// pairs were found at, for a restart inside the next window. In the sequential coupling this follows a
// remesh only (the graph's own exchange ran before it, on the old mesh): outputs, health checks and
// checkpoints between windows then see a fluid consistent with the solid.
void FluidSolidModel::exchange_solid_to_fluid(const StepContext&) {
  timed(to_fluid_time_, [&] {
    to_fluid_->exchange();
    if (concurrent_) keep_exchange_positions();
  });
}

void FluidSolidModel::remesh_fluid(const StepContext& taken) {
  adapt_fluid_mesh(static_cast<double>(taken.step + 1) * taken.dt);
}

void FluidSolidModel::adapt_fluid_mesh(double time) {
  const auto t0 = std::chrono::steady_clock::now();
  fluid_.remesh(adapter_->make(), time);
  fluid_mesh_changed();
  remesh_time_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++remesh_time_.calls;
}

void FluidSolidModel::fluid_mesh_changed() {
  to_fluid_->fluid_mesh_changed();
  to_solid_->set_fluid_volume(fluid_.solver().volumes());
}

// The stored fluid state becomes the window's end; mid-window (a checkpoint, the end of a stopped run) it
// stays marked so, and at the window's end exchange_fluid_to_solid clears the mark.
void FluidSolidModel::join() {
  if (!concurrent_ || !concurrent_->running()) return;
  concurrent_->join();
  coupling::state::fluid_ahead.in(store_)[0] = 1;
}

// What the fluid task may touch while the graph runs the solid's sub-steps: the fluid step's declared
// columns (its state and the coupling columns it reads). The run loop checks them against every system of
// the graph (Simulation, engine/schedule access_conflict): none may write one of them or read one it
// writes, and since every fluid column belongs to the fluid's tables, a solid column in this list would be
// caught the same way. The exchanges, which do read and write both sides, run only after the join.
Access FluidSolidModel::access() const {
  return fluid_step_ ? fluid_step_->access() : Access{};
}

std::vector<SystemTiming> FluidSolidModel::timings() const {
  std::vector<SystemTiming> out;
  if (concurrent_)
    out = {{"fluid_step", concurrent_->task_seconds(), concurrent_->steps()},
           {"fluid_wait", concurrent_->wait_seconds(), concurrent_->steps()},
           to_solid_time_,
           to_fluid_time_};
  if (adapter_) out.push_back(remesh_time_);
  return out;
}

std::optional<std::string> FluidSolidModel::check_health(const StepContext& after) {
  const Table& state = store_.table(coupling::state_table);
  const auto force = coupling::state::force.in(state);
  const auto penalty = coupling::state::penalty.in(state);
  const auto absorption = coupling::state::absorption.in(state);
  const double t_fluid = static_cast<double>(after.step / settings_.substeps) * settings_.dt;
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(force[d]))
      return fmt::format(
          "the fluid's force on the solid is not finite after the fluid step ending at t = {:.6g} s. Likely "
          "cause: the fluid step diverged (its own guard reports why), or the solid moved so fast that the "
          "absorption overflowed. What to change: lower fluid.dt (with it the solid's window of "
          "fluid_solid.substeps steps).",
          t_fluid);
  if (coupling::state::growing.in(state)[0] >= 4) {
    const Table& nodes = store_.table(solid::node_table);
    double mass = 0.0;
    for (double m : solid::node::mass.in(nodes)) mass += m;
    return fmt::format(
        "the fluid's force on the solid oscillates with a growing amplitude: its change has flipped sign and "
        "grown for 4 fluid steps in a row, up to t = {:.6g} s (force now ({:.4g}, {:.4g}, {:.4g}) N). Likely "
        "cause: the added-mass instability of the staggered exchange. The solid's mean density is {:.3g} "
        "times the fluid's ({:.6g} kg/m^3); when the mass of fluid the solid must push aside is comparable "
        "to its own, the force of one window over-corrects the next. What to change: set "
        "fluid_solid.added_mass: 1 (a virtual mass that cancels the lagged added-mass force), or make the "
        "solid denser than the fluid. A smaller fluid.dt does not help this instability.{}",
        t_fluid, force[0], force[1], force[2], mass / (settings_.rho * solid_volume_), settings_.rho,
        settings_.oscillation_lag == 2
            ? " With fluid_solid.coupling: concurrent the fluid answers the solid a window later still; "
              "fluid_solid.coupling: sequential is the more stable choice for light solids."
            : "");
  }
  // Newton's third law: the solid's penalty force is minus what the fluid's absorption felt, exactly but
  // for round-off (kernels/fluid_solid_exchange.hpp), also where solid tets overlap (the pair weights).
  // A gap means the absorption the fluid stepped with is not the one the pairs were weighted for.
  const double scale =
      coupling::state::penalty_scale.in(state)[0];  // sum of |pair penalty|: the round-off scale
  double gap = 0.0;
  for (int d = 0; d < 3; ++d) gap = std::max(gap, std::abs(penalty[d] - absorption[d]));
  if (gap > 1e-9 * scale && gap > 0.0)
    return fmt::format(
        "the fluid's absorption force ({:.6g}, {:.6g}, {:.6g}) N and the solid's penalty force ({:.6g}, "
        "{:.6g}, "
        "{:.6g}) N differ by {:.3g} N after the fluid step ending at t = {:.6g} s: momentum is not exchanged "
        "equal and opposite. Likely cause: the absorption the fluid stepped with differs from the one the "
        "exchange weighted its pairs for (an internal inconsistency of the coupling, not of the scene). What "
        "to "
        "change: nothing in the scene fixes it; report it with the scene and the step.",
        absorption[0], absorption[1], absorption[2], penalty[0], penalty[1], penalty[2], gap, t_fluid);
  return std::nullopt;
}

void FluidSolidModel::output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) {
  for (XdmfGrid& g : grids) {
    if (g.name == "fluid" && wants_field(fields, "solid_fraction")) {
      const Table& ft = store_.table(fluid::tet_table);
      g.fields.push_back({"solid_fraction", Center::cell, 1, ElementType::f64,
                          coupling::cell::solid_fraction.in(ft).data(), ft.size()});
      if (settings_.network_inlet)  // which cells hold the network's fluid, not the surrounding fluid's
        g.fields.push_back({"network_cell", Center::cell, 1, ElementType::f64,
                            coupling::cell::network_cell.in(ft).data(), ft.size()});
    }
    if (g.name == "solid" && wants_field(fields, "fluid_force")) {
      const Table& nodes = store_.table(solid::node_table);
      g.fields.push_back({"fluid_force", Center::node, 3, ElementType::f64,
                          nodes.span<double>(node_force_column(NodeForceSource::fluid)).data(),
                          nodes.size()});
    }
  }
}

void FluidSolidModel::metrics(double, std::vector<std::pair<std::string, double>>& row) {
  const Table& state = store_.table(coupling::state_table);
  const auto force = coupling::state::force.in(state);
  const auto penalty = coupling::state::penalty.in(state);
  row.emplace_back("fluid_solid_force_x", force[0]);
  row.emplace_back("fluid_solid_force_y", force[1]);
  row.emplace_back("fluid_solid_force_z", force[2]);
  row.emplace_back("fluid_solid_penalty_x", penalty[0]);
  row.emplace_back("fluid_solid_penalty_y", penalty[1]);
  row.emplace_back("fluid_solid_penalty_z", penalty[2]);
  row.emplace_back("fluid_solid_solid_volume", coupling::state::solid_volume.in(state)[0]);
  row.emplace_back("fluid_solid_cut_cells", static_cast<double>(coupling::state::cut_cells.in(state)[0]));
  row.emplace_back("fluid_solid_pairs", static_cast<double>(coupling::state::pairs.in(state)[0]));
  // The pressure range over the nodes of the cells the fluid fills (solid fraction below 0.5): the real
  // fluid's, without the fictitious fluid inside the solid, nor the cells the cracks' network owns (their
  // fluid is the network's, its pressure the network's vertices').
  const Table& ft = store_.table(fluid::tet_table);
  const auto fraction = coupling::cell::solid_fraction.in(ft);
  const auto owned = settings_.network_inlet ? coupling::cell::network_cell.in(ft) : std::span<double>{};
  const auto tets = fluid::tet::nodes.in(ft);
  const auto p = fluid::node::pressure.in(store_);
  double pmin = 0.0, pmax = 0.0;
  bool any = false;
  for (size_t k = 0; k < fraction.size(); ++k) {
    if (!(fraction[k] < 0.5) || (!owned.empty() && owned[k] != 0.0)) continue;
    for (int a = 0; a < 4; ++a) {
      const double q = p[static_cast<size_t>(tets[4 * k + a])];
      pmin = any ? std::min(pmin, q) : q;
      pmax = any ? std::max(pmax, q) : q;
      any = true;
    }
  }
  row.emplace_back("fluid_region_pressure_min", pmin);
  row.emplace_back("fluid_region_pressure_max", pmax);
  if (settings_.network_inlet) {
    row.emplace_back("fluid_solid_inlet_pressure", fracture_flow::books::inlet_pressure.in(store_)[0]);
    row.emplace_back("fluid_solid_inlet_sink_mass", coupling::state::inlet_sink_mass.in(state)[0]);
    row.emplace_back("fluid_solid_inlet_injected", coupling::state::inlet_injected.in(state)[0]);
  }
}

void FluidSolidModel::summarize(nlohmann::json& summary) const {
  const Table& state = store_.table(coupling::state_table);
  auto& s = summary["fluid_solid"];
  s["substeps"] = settings_.substeps;
  s["beta"] = settings_.beta;
  if (spec_.relaxation_time > 0.0) s["relaxation_time"] = spec_.relaxation_time;
  s["added_mass"] = settings_.added_mass;
  s["coupling"] = spec_.coupling == FluidSolidSpec::Coupling::concurrent ? "concurrent" : "sequential";
  s["force_model"] = settings_.volume_force ? "volume" : "wetted_faces";
  s["wetted_faces"] = pairs_.wet_faces.size();
  s["wetted_faces_outside_fluid"] = pairs_.wet_outside;
  s["exchanges"] = coupling::state::exchanges.in(state)[0];
  s["pairs"] = coupling::state::pairs.in(state)[0];
  s["cut_cells"] = coupling::state::cut_cells.in(state)[0];
  s["solid_volume"] = solid_volume_;
  s["solid_volume_in_fluid"] = coupling::state::solid_volume.in(state)[0];
  const auto f = coupling::state::force.in(state);
  const auto p = coupling::state::penalty.in(state);
  const auto a = coupling::state::absorption.in(state);
  s["force"] = {f[0], f[1], f[2]};
  s["penalty"] = {p[0], p[1], p[2]};
  s["absorption"] = {a[0], a[1], a[2]};
}

}  // namespace rift
