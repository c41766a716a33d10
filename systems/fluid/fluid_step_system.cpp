#include "systems/fluid/fluid_step_system.hpp"

#include <algorithm>
#include <span>

#include "systems/fluid/fluid_tables.hpp"

namespace rift {

Access FluidStepSystem::access() const {
  using fluid::col;
  Access a;
  a.writes = {fluid::node::velocity.key(), fluid::node::pressure.key(), fluid::node::previous_velocity.key(),
              fluid::tet::pressure_matrix_coefficient.key(), fluid::tet::pressure_subscale.key()};
  for (const auto& columns :
       {std::span<const char* const>(fluid::step_counts), std::span<const char* const>(fluid::step_flags),
        std::span<const char* const>(fluid::step_measures)})
    for (const char* c : columns) a.writes.push_back(col(fluid::step_table, c));
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
  Table& step = store_.table(fluid::step_table);
  const fluid::FluidStepReport& r = last_;
  auto count = [&](const char* c) -> int64_t& { return step.span<int64_t>(c)[0]; };
  auto measure = [&](const char* c) -> double& { return step.span<double>(c)[0]; };
  count("picard_iterations") = r.picard_iterations;
  count("velocity_iterations") = r.velocity_iterations;
  count("schur_iterations") = r.schur_iterations;
  count("pressure_iterations") = r.pressure_iterations;
  count("amg_setups") = r.amg_setups;
  step.span<uint8_t>("converged")[0] = r.converged ? 1 : 0;
  measure("velocity_change") = r.velocity_change;
  measure("pressure_change") = r.pressure_change;
  measure("divergence_l2") = r.divergence_l2;
  measure("divergence_max") = r.divergence_max;
  measure("cfl") = r.cfl;
  if (!r.converged) count("picard_failures") += 1;
  double& max_cfl = step.span<double>("max_cfl")[0];
  double& max_div = step.span<double>("max_divergence")[0];
  max_cfl = std::max(max_cfl, r.cfl);
  max_div = std::max(max_div, r.divergence_max);
}

void FluidStepSystem::restore_report() {
  const Table& step = store_.table(fluid::step_table);
  auto v = [&](const char* c) { return step.span<const double>(c)[0]; };
  auto n = [&](const char* c) { return static_cast<int>(step.span<const int64_t>(c)[0]); };
  fluid::FluidStepReport& r = last_;
  r.picard_iterations = n("picard_iterations");
  r.converged = step.span<const uint8_t>("converged")[0] != 0;
  r.velocity_iterations = n("velocity_iterations");
  r.schur_iterations = n("schur_iterations");
  r.pressure_iterations = n("pressure_iterations");
  r.amg_setups = n("amg_setups");
  r.velocity_change = v("velocity_change");
  r.pressure_change = v("pressure_change");
  r.divergence_l2 = v("divergence_l2");
  r.divergence_max = v("divergence_max");
  r.cfl = v("cfl");
}

}  // namespace rift
