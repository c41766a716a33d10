#include "systems/fluid/fluid_step_system.hpp"

#include <algorithm>
#include <span>

#include "systems/fluid/fluid_tables.hpp"

namespace rift {

Access FluidStepSystem::access() const {
  Access a;
  a.writes = {fluid::node::velocity.key(), fluid::node::pressure.key(), fluid::node::previous_velocity.key(),
              fluid::tet::pressure_matrix_coefficient.key(), fluid::tet::pressure_subscale.key()};
  for (const auto& c : fluid::step::counts) a.writes.push_back(c.key());
  for (const auto& c : fluid::step::flags) a.writes.push_back(c.key());
  for (const auto& c : fluid::step::measures) a.writes.push_back(c.key());
  a.reads = coupling_reads_;
  return a;
}

void FluidStepSystem::run(const StepContext& ctx) {
  // The run's clock is authoritative (t = step x dt): no drift from summing dt, and a restart starts
  // from the same time bit for bit.
  advance(static_cast<double>(ctx.step + 1 - every_) * ctx.dt);
  commit();
}

void FluidStepSystem::advance(double start_time) {
  solver_.set_time(start_time);
  last_ = solver_.advance();
}

void FluidStepSystem::commit() {
  solver_.commit();
  namespace fs = fluid::step;
  const fluid::FluidStepReport& r = last_;
  auto value = [&]<class T>(const ColumnRef<T>& c) -> T& { return c.in(store_)[0]; };
  value(fs::picard_iterations) = r.picard_iterations;
  value(fs::velocity_iterations) = r.velocity_iterations;
  value(fs::schur_iterations) = r.schur_iterations;
  value(fs::pressure_iterations) = r.pressure_iterations;
  value(fs::amg_setups) = r.amg_setups;
  value(fs::converged) = r.converged ? 1 : 0;
  value(fs::velocity_change) = r.velocity_change;
  value(fs::pressure_change) = r.pressure_change;
  value(fs::divergence_l2) = r.divergence_l2;
  value(fs::divergence_max) = r.divergence_max;
  value(fs::cfl) = r.cfl;
  if (!r.converged) value(fs::picard_failures) += 1;
  double& max_cfl = value(fs::max_cfl);
  double& max_div = value(fs::max_divergence);
  max_cfl = std::max(max_cfl, r.cfl);
  max_div = std::max(max_div, r.divergence_max);
}

void FluidStepSystem::restore_report() {
  namespace fs = fluid::step;
  auto v = [&](const ColumnRef<double>& c) { return c.read(store_)[0]; };
  auto n = [&](const ColumnRef<int64_t>& c) { return static_cast<int>(c.read(store_)[0]); };
  fluid::FluidStepReport& r = last_;
  r.picard_iterations = n(fs::picard_iterations);
  r.converged = fs::converged.read(store_)[0] != 0;
  r.velocity_iterations = n(fs::velocity_iterations);
  r.schur_iterations = n(fs::schur_iterations);
  r.pressure_iterations = n(fs::pressure_iterations);
  r.amg_setups = n(fs::amg_setups);
  r.velocity_change = v(fs::velocity_change);
  r.pressure_change = v(fs::pressure_change);
  r.divergence_l2 = v(fs::divergence_l2);
  r.divergence_max = v(fs::divergence_max);
  r.cfl = v(fs::cfl);
}

}  // namespace rift
