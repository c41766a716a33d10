#include "systems/fluid/fluid_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/scene/output_fields.hpp"
#include "engine/scene/suggest.hpp"
#include "systems/fluid/fluid_tables.hpp"

namespace rift {

namespace {

std::vector<fluid::FluidBoundary> boundaries_for(const FluidSpec& spec, const TetMesh& mesh) {
  std::vector<fluid::FluidBoundary> out;
  for (size_t i = 0; i < spec.boundaries.size(); ++i) {
    const FluidBoundarySpec& b = spec.boundaries[i];
    if (mesh.surface_index(b.surface) < 0)
      throw Error("fluid.boundaries[" + std::to_string(i) + "].surface: the mesh has no surface '" +
                  b.surface + "'" + hint(did_you_mean(b.surface, mesh.surface_names)) +
                  "; its surfaces are: " + join_names(mesh.surface_names));
    fluid::FluidBoundary fb;
    fb.surface = b.surface;
    fb.kind = b.kind;
    if (b.kind == FluidBoundarySpec::Kind::velocity) {
      // The surface's bounding box, for a parabolic profile.
      std::array<double, 3> lo{}, hi{};
      lo.fill(std::numeric_limits<double>::infinity());
      hi.fill(-std::numeric_limits<double>::infinity());
      const int32_t s = mesh.surface_index(b.surface);
      for (size_t t = 0; t < mesh.triangles.size(); ++t)
        if (mesh.triangle_surface[t] == s)
          for (int32_t n : mesh.triangles[t])
            for (int d = 0; d < 3; ++d) {
              lo[d] = std::min(lo[d], mesh.nodes[n][d]);
              hi[d] = std::max(hi[d], mesh.nodes[n][d]);
            }
      for (int d = 0; d < 3; ++d)
        if (b.parabolic[d] && !(hi[d] > lo[d]))
          throw Error("fluid.boundaries[" + std::to_string(i) + "].parabolic: surface '" + b.surface +
                      "' has no extent along " + "xyz"[d] + ", so no profile across it");
      fb.velocity = [dir = b.direction, f = b.function, axes = b.parabolic, lo, hi](const fluid::Vec3& x,
                                                                                    double t) {
        double s = f(t);
        for (int d = 0; d < 3; ++d)
          if (axes[d]) s *= 4.0 * (x[d] - lo[d]) * (hi[d] - x[d]) / ((hi[d] - lo[d]) * (hi[d] - lo[d]));
        return fluid::Vec3{s * dir[0], s * dir[1], s * dir[2]};
      };
    } else if (b.kind == FluidBoundarySpec::Kind::pressure) {
      fb.pressure = [f = b.function](const fluid::Vec3&, double t) { return f(t); };
    }
    out.push_back(std::move(fb));
  }
  return out;
}

fluid::FluidSettings settings_for(const FluidSpec& spec) {
  fluid::FluidSettings s;
  s.rho = spec.density;
  s.mu = spec.viscosity;
  s.dt = spec.dt;
  s.theta = spec.theta;
  s.convection = spec.convection;
  s.supg = spec.supg;
  s.dynamic_subscale = spec.dynamic_subscale;
  s.coupling = spec.coupling;
  s.picard_max_iterations = spec.picard_max_iterations;
  s.picard_tol = spec.picard_tolerance;
  s.velocity_rel_tol = spec.velocity_tolerance;
  s.velocity_max_iterations = spec.velocity_max_iterations;
  s.schur_rel_tol = spec.schur_tolerance;
  s.schur_max_iterations = spec.schur_max_iterations;
  s.schur_restart = spec.schur_restart;
  s.pressure_solver.rel_tol = spec.pressure_tolerance;
  s.pressure_solver.max_iterations = spec.pressure_max_iterations;
  return s;
}

}  // namespace

FluidModel::FluidModel(Store& store, const TetMesh& mesh, const FluidSpec& spec, int64_t substeps,
                       std::vector<std::string> coupling_reads)
    : store_(store), spec_(spec), substeps_(substeps), surface_names_(mesh.surface_names) {
  build_solver(mesh);
  Table& nodes = store_.add_table(fluid::node_table);
  fluid::node::x.create(nodes);
  fluid::node::velocity.create(nodes);
  fluid::node::pressure.create(nodes);
  fluid::node::previous_velocity.create(nodes);
  Table& tets = store_.add_table(fluid::tet_table);
  fluid::tet::nodes.create(tets).indexes(IndexTarget::rows_of(fluid::node_table));
  fluid::tet::pressure_matrix_coefficient.create(tets);
  fluid::tet::pressure_subscale.create(tets);
  if (spec.adapt) {
    Table& faces = store_.add_table(fluid::boundary_table);
    fluid::boundary::nodes.create(faces).indexes(IndexTarget::rows_of(fluid::node_table));
    fluid::boundary::surface.create(faces).indexes(IndexTarget::list_of(mesh.surface_names.size()));
  }
  Table& step = store_.add_table(fluid::step_table);
  for (const auto& c : fluid::step::counts) c.create(step);
  for (const auto& c : fluid::step::flags) c.create(step);
  for (const auto& c : fluid::step::measures) c.create(step);
  if (spec.adapt) fluid::step::remeshes.create(step);
  step.resize(1);
  store_mesh(mesh);
  use_store_state();
  const auto v0 = spec.initial_velocity;
  solver_->set_velocity([v0](const fluid::Vec3&, double) { return v0; });
  solver_->set_pressure(spec.initial_pressure);
  step_ = std::make_unique<FluidStepSystem>(store_, *solver_, substeps_, std::move(coupling_reads));
}

void FluidModel::build_solver(const TetMesh& mesh) {
  auto bcs = boundaries_for(spec_, mesh);
  try {
    fluid::FluidSolver solver(mesh, settings_for(spec_), std::move(bcs));
    if (solver_)
      *solver_ = std::move(solver);
    else
      solver_ = std::make_unique<fluid::FluidSolver>(std::move(solver));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(std::string("fluid: ") + e.what());
  }
  if (spec_.body_force != std::array<double, 3>{}) {
    const auto f = spec_.body_force;
    solver_->set_body_force([f](const fluid::Vec3&, double) { return f; });
  }
}

void FluidModel::use_store_state() {
  solver_->use_state(
      {&fluid::node::velocity.column(store_), &fluid::node::previous_velocity.column(store_),
       &fluid::node::pressure.column(store_), &fluid::tet::pressure_matrix_coefficient.column(store_),
       &fluid::tet::pressure_subscale.column(store_), &fluid::step::has_previous.column(store_)});
}

FluidModel::~FluidModel() = default;

// Outputs and metrics read the fluid's committed state: with the concurrent coupling a step may be in
// flight in a task while the run loop writes them.
void FluidModel::cell_fields() {
  const auto u = fluid::node::velocity.in(store_);
  const auto conn = solver_->tets();
  const auto grad = solver_->gradients();
  const auto h = solver_->element_sizes();
  const size_t nt = h.size();
  divergence_.assign(nt, 0.0);
  cfl_.assign(nt, 0.0);
  for (size_t t = 0; t < nt; ++t) {
    double div = 0.0, ubar[3] = {0, 0, 0};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) {
        const double ua = u[3 * static_cast<size_t>(conn[4 * t + a]) + d];
        div += grad[12 * t + 3 * a + d] * ua;
        ubar[d] += 0.25 * ua;
      }
    divergence_[t] = div;
    cfl_[t] = std::sqrt(ubar[0] * ubar[0] + ubar[1] * ubar[1] + ubar[2] * ubar[2]) * spec_.dt / h[t];
  }
}

double FluidModel::kinetic_energy() const {
  const auto u = fluid::node::velocity.in(store_);
  double e = 0.0;
  const auto node_volume = solver_->node_volumes();
  for (size_t n = 0; n < node_volume.size(); ++n)
    e += node_volume[n] * (u[3 * n] * u[3 * n] + u[3 * n + 1] * u[3 * n + 1] + u[3 * n + 2] * u[3 * n + 2]);
  return 0.5 * spec_.density * e;
}

std::optional<std::string> FluidModel::check_health(const StepContext& after) {
  if (after.step % substeps_ != 0) return std::nullopt;  // the fluid did not step (a solid sub-step)
  const fluid::FluidStepReport& r = step_->last_report();
  const auto u = solver_->velocity();
  const auto p = solver_->pressure();
  const auto x = solver_->nodes();
  size_t bad = 0, first = 0;
  for (size_t n = 0; n < p.size(); ++n)
    if (!std::isfinite(p[n]) || !std::isfinite(u[3 * n]) || !std::isfinite(u[3 * n + 1]) ||
        !std::isfinite(u[3 * n + 2]))
      if (bad++ == 0) first = n;
  const std::string advice =
      "What to change: lower fluid.dt (the step's CFL was " + fmt::format("{:.3g}", r.cfl) +
      "), use scheme: backward_euler and supg: true for convection-dominated flow, refine the mesh, or check "
      "the boundary conditions: their magnitudes, and that they admit a solution (an outflow or pressure "
      "surface for a driven inflow).";
  if (bad > 0)
    return fmt::format(
        "{} fluid nodes have a non-finite velocity or pressure after step {} (t = {:.6g} s); first: node {} "
        "at ({:.4g}, {:.4g}, {:.4g}) m. Likely cause: the step diverged (a dt too large for the flow), or a "
        "boundary value, body force or initial velocity so large that the arithmetic overflowed. {}",
        bad, after.step, after.time, first, x[3 * first], x[3 * first + 1], x[3 * first + 2], advice);
  if (!r.converged && spec_.on_picard_failure == FluidSpec::OnPicardFailure::stop) {
    if (!r.linear_converged)
      return fmt::format(
          "the fluid's linear solve did not converge in step {} (t = {:.6g} s), Picard iteration {}: {}. A "
          "step whose solve stops at its cap is not a solution, however small its Picard change. Likely "
          "cause: an ill-conditioned step (extreme viscosity, density or absorption contrasts for this dt "
          "and mesh); with fluid.pressure_subscale: quasi_static, a low-viscosity fluid near rest (the "
          "stabilisation's tau = h^2 / (4 mu) far above dt / rho). What to change: fluid.pressure_subscale: "
          "dynamic (bounds tau by dt / rho, same steady state), raise fluid.schur_max_iterations (with "
          "fluid.schur_restart as large: a restart discards the Krylov space) or fluid.schur_tolerance, "
          "lower fluid.dt, or refine the mesh where the contrast is.",
          after.step, after.time, r.picard_iterations,
          r.momentum_failures > 0
              ? fmt::format("{} momentum (BiCGSTAB) solves stopped at {} iterations", r.momentum_failures,
                            spec_.velocity_max_iterations)
              : fmt::format("FGMRES on the pressure Schur complement stopped at its cap "
                            "(fluid.schur_max_iterations = {}) with residual {:.3g}, {:.3g} x its target",
                            spec_.schur_max_iterations, r.schur_residual, r.schur_residual / r.schur_target));
    cell_fields();
    const size_t worst = static_cast<size_t>(std::max_element(cfl_.begin(), cfl_.end()) - cfl_.begin());
    const auto conn = solver_->tets();
    double c[3] = {0, 0, 0};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) c[d] += 0.25 * x[3 * static_cast<size_t>(conn[4 * worst + a]) + d];
    return fmt::format(
        "the fluid's Picard iteration did not converge in step {} (t = {:.6g} s): after {} iterations "
        "(fluid.picard_max_iterations) the relative changes are {:.3g} (velocity) and {:.3g} (pressure), "
        "fluid.picard_tolerance is {:.3g}; the largest CFL number {:.3g} is at ({:.4g}, {:.4g}, {:.4g}) m. "
        "Likely cause: strong convection for this step (CFL > 1) or a sudden change of a boundary value. "
        "{} Or raise fluid.picard_max_iterations / fluid.picard_tolerance, or set fluid.on_picard_failure: "
        "continue when a fixed number of iterations per step is meant (iterated projection).",
        after.step, after.time, r.picard_iterations, r.velocity_change, r.pressure_change,
        spec_.picard_tolerance, cfl_[worst], c[0], c[1], c[2], advice);
  }
  return std::nullopt;
}

void FluidModel::output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) {
  cell_fields();
  const Table& nodes = store_.table(fluid::node_table);
  const Table& tets = store_.table(fluid::tet_table);
  XdmfGrid g{"fluid",
             Topology::tetrahedron,
             fluid::node::x.in(nodes).data(),
             nodes.size(),
             fluid::tet::nodes.in(tets).data(),
             tets.size(),
             static_cast<uint64_t>(mesh_revision()),
             false,
             {}};
  if (wants_field(fields, "velocity"))
    g.fields.push_back({"velocity", Center::node, 3, ElementType::f64, fluid::node::velocity.in(nodes).data(),
                        nodes.size()});
  if (wants_field(fields, "pressure"))
    g.fields.push_back({"pressure", Center::node, 1, ElementType::f64, fluid::node::pressure.in(nodes).data(),
                        nodes.size()});
  if (wants_field(fields, "divergence"))
    g.fields.push_back({"divergence", Center::cell, 1, ElementType::f64, divergence_.data(), tets.size()});
  if (wants_field(fields, "cfl"))
    g.fields.push_back({"cfl", Center::cell, 1, ElementType::f64, cfl_.data(), tets.size()});
  grids.push_back(std::move(g));
}

void FluidModel::metrics(double, std::vector<std::pair<std::string, double>>& row) {
  namespace fs = fluid::step;
  auto v = [&](const ColumnRef<double>& c) { return c.read(store_)[0]; };
  auto n = [&](const ColumnRef<int64_t>& c) { return static_cast<double>(c.read(store_)[0]); };
  row.emplace_back("fluid_picard_iterations", n(fs::picard_iterations));
  row.emplace_back("fluid_picard_converged", static_cast<double>(fs::converged.read(store_)[0]));
  row.emplace_back("fluid_velocity_iterations", n(fs::velocity_iterations));
  row.emplace_back("fluid_schur_iterations", n(fs::schur_iterations));
  row.emplace_back("fluid_pressure_iterations", n(fs::pressure_iterations));
  row.emplace_back("fluid_divergence_l2", v(fs::divergence_l2));
  row.emplace_back("fluid_divergence_max", v(fs::divergence_max));
  row.emplace_back("fluid_cfl", v(fs::cfl));
  row.emplace_back("fluid_kinetic_energy", kinetic_energy());
  const auto u = fluid::node::velocity.in(store_);
  double speed2 = 0.0;
  for (size_t n = 0; n < u.size() / 3; ++n)
    speed2 =
        std::max(speed2, u[3 * n] * u[3 * n] + u[3 * n + 1] * u[3 * n + 1] + u[3 * n + 2] * u[3 * n + 2]);
  row.emplace_back("fluid_max_speed", std::sqrt(speed2));
  const auto p = fluid::node::pressure.in(store_);
  double pmin = p.empty() ? 0.0 : p[0], pmax = pmin;
  for (double q : p) {
    pmin = std::min(pmin, q);
    pmax = std::max(pmax, q);
  }
  row.emplace_back("fluid_pressure_min", pmin);
  row.emplace_back("fluid_pressure_max", pmax);
}

// The fluid's mesh is continuous: its own tets make the dual graph. Each tet weighs 1 (the assembly's
// work is per tet and the mesh is the same everywhere); a ghost node's exchange is one value of a Krylov
// vector, 8 B, once per solver iteration, so no time per step is predicted.
void FluidModel::partition_work(std::vector<PartitionWork>& domains) const {
  const auto nodes = fluid::tet::nodes.read(store_);
  PartitionWork work;
  work.domain = "fluid";
  work.nodes = int32_t(store_.table(fluid::node_table).size());
  work.node_bytes = 8;
  work.graph_tets.resize(nodes.size() / 4);
  for (size_t t = 0; t < work.graph_tets.size(); ++t)
    for (size_t c = 0; c < 4; ++c) work.graph_tets[t][c] = nodes[4 * t + c];
  work.tet_weight.assign(work.graph_tets.size(), 1);
  work.elements.push_back({"tets", 4, nodes, 1});
  domains.push_back(std::move(work));
}

void FluidModel::summarize(nlohmann::json& summary) const {
  namespace fs = fluid::step;
  auto v = [&](const ColumnRef<double>& c) { return c.read(store_)[0]; };
  auto n = [&](const ColumnRef<int64_t>& c) { return c.read(store_)[0]; };
  auto& s = summary["fluid"];
  s["nodes"] = solver_->node_count();
  s["tets"] = solver_->volumes().size();
  if (spec_.adapt) s["remeshes"] = mesh_revision();
  s["dt"] = spec_.dt;
  s["kinetic_energy"] = kinetic_energy();
  s["picard_failures"] = n(fs::picard_failures);
  s["max_cfl"] = v(fs::max_cfl);
  s["max_divergence"] = v(fs::max_divergence);
  s["last_step"] = {{"picard_iterations", n(fs::picard_iterations)},
                    {"converged", fs::converged.read(store_)[0] != 0},
                    {"velocity_iterations", n(fs::velocity_iterations)},
                    {"schur_iterations", n(fs::schur_iterations)},
                    {"pressure_iterations", n(fs::pressure_iterations)},
                    {"velocity_change", v(fs::velocity_change)},
                    {"divergence_l2", v(fs::divergence_l2)},
                    {"divergence_max", v(fs::divergence_max)},
                    {"cfl", v(fs::cfl)}};
}

int64_t FluidModel::mesh_revision() const {
  return spec_.adapt ? fluid::step::remeshes.read(store_)[0] : 0;
}

// The checkpoint's values are in the fluid tables already, which are the solver's state.
void FluidModel::restored(const StepContext& at) {
  if (spec_.adapt) {  // the checkpoint's mesh, maybe not the scene's first one
    build_solver(mesh_from_store());
    use_store_state();
  }
  solver_->restored(at.time);
  step_->restore_report();
}

}  // namespace rift
