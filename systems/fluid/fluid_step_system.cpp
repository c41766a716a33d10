#include "systems/fluid/fluid_step_system.hpp"

#include <algorithm>

#include "systems/fluid/fluid_tables.hpp"

namespace rift {

Access FluidStepSystem::access() const {
  using fluid::col;
  Access a;
  a.writes = {col(fluid::node_table, "velocity"), col(fluid::node_table, "pressure"),
              col(fluid::node_table, "previous_velocity"),
              col(fluid::tet_table, "pressure_matrix_coefficient"),
              col(fluid::tet_table, "pressure_subscale")};
  for (const char* c : fluid::step_columns) a.writes.push_back(col(fluid::step_table, c));
  a.writes.push_back(col(fluid::step_table, "has_previous"));
  a.reads = coupling_reads_;
  return a;
}

void FluidStepSystem::run(const StepContext& ctx) {
  // The run's clock is authoritative (t = step x dt): no drift from summing dt, and a restart starts
  // from the same time bit for bit.
  if ((ctx.step + 1) % every_ != 0) return;
  advance(static_cast<double>(ctx.step + 1 - every_) * ctx.dt);
  publish();
}

void FluidStepSystem::advance(double start_time) {
  solver_.set_time(start_time);
  last_ = solver_.step();
}

void FluidStepSystem::publish() {
  Table& nodes = store_.table(fluid::node_table);
  const auto u = solver_.velocity();
  const auto p = solver_.pressure();
  const auto c = solver_.pressure_matrix_coefficients();
  std::copy(u.begin(), u.end(), nodes.span<double>("velocity").begin());
  std::copy(p.begin(), p.end(), nodes.span<double>("pressure").begin());
  // u^{n-1} of the next step's extrapolated start (FluidSettings::picard_extrapolate): run state.
  const auto u_prev = solver_.previous_velocity();
  std::copy(u_prev.begin(), u_prev.end(), nodes.span<double>("previous_velocity").begin());
  store_.table(fluid::step_table).span<double>("has_previous")[0] = solver_.has_previous() ? 1.0 : 0.0;
  Table& tets = store_.table(fluid::tet_table);
  std::copy(c.begin(), c.end(), tets.span<double>("pressure_matrix_coefficient").begin());
  const auto sub = solver_.pressure_subscale();
  std::copy(sub.begin(), sub.end(), tets.span<double>("pressure_subscale").begin());
  Table& step = store_.table(fluid::step_table);
  const fluid::FluidStepReport& r = last_;
  const double values[] = {static_cast<double>(r.picard_iterations),
                           r.converged ? 1.0 : 0.0,
                           static_cast<double>(r.velocity_iterations),
                           static_cast<double>(r.schur_iterations),
                           static_cast<double>(r.pressure_iterations),
                           static_cast<double>(r.amg_setups),
                           r.velocity_change,
                           r.pressure_change,
                           r.divergence_l2,
                           r.divergence_max,
                           r.cfl};
  for (size_t i = 0; i < std::size(values); ++i) step.span<double>(fluid::step_columns[i])[0] = values[i];
  if (!r.converged) step.span<double>("picard_failures")[0] += 1.0;
  double& max_cfl = step.span<double>("max_cfl")[0];
  double& max_div = step.span<double>("max_divergence")[0];
  max_cfl = std::max(max_cfl, r.cfl);
  max_div = std::max(max_div, r.divergence_max);
}

void FluidStepSystem::restore_report() {
  const Table& step = store_.table(fluid::step_table);
  auto v = [&](const char* c) { return step.span<const double>(c)[0]; };
  fluid::FluidStepReport& r = last_;
  r.picard_iterations = static_cast<int>(v("picard_iterations"));
  r.converged = v("converged") != 0.0;
  r.velocity_iterations = static_cast<int>(v("velocity_iterations"));
  r.schur_iterations = static_cast<int>(v("schur_iterations"));
  r.pressure_iterations = static_cast<int>(v("pressure_iterations"));
  r.amg_setups = static_cast<int>(v("amg_setups"));
  r.velocity_change = v("velocity_change");
  r.pressure_change = v("pressure_change");
  r.divergence_l2 = v("divergence_l2");
  r.divergence_max = v("divergence_max");
  r.cfl = v("cfl");
}

}  // namespace rift
