// An in-situ stress state set at t = 0 launches no wave (scenes/validation/in_situ_block.yaml), and the
// runtime guard stops an unstable run with a diagnosis rather than a NaN field.
#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift::validation {
namespace {

// A stress mismatch of |sigma0| = 10 MPa would give particle velocities near |sigma0| / (rho c_p) =
// 0.89 m/s. What is left is round-off in sums of forces of order |sigma0| h^2 that cancel: the bound
// 1e-9 m/s is eight orders below the mismatch scale and far above that round-off.
TEST(InSituStress, JointedBlockStartsInEquilibrium) {
  const Scene scene = validation_scene("in_situ_block.yaml");
  double largest_speed = 0.0, largest_damage = 0.0;
  const RunResult r = run_watching(scene, 1, [&](Simulation& sim) {
    const auto v = sim.world().store.table("solid_node").span<const double>("v");
    for (double c : v) largest_speed = std::max(largest_speed, std::abs(c));
    for (double d : sim.world().store.table("solid_joint").span<const double>("damage"))
      largest_damage = std::max(largest_damage, d);
  });
  EXPECT_GT(r.steps, 100);
  EXPECT_LT(largest_speed, 1e-9) << "largest velocity component " << largest_speed << " m/s";
  EXPECT_EQ(largest_damage, 0.0);
  RecordProperty("largest_speed", std::to_string(largest_speed));
}

// The same block without the joints' initial offsets is not in equilibrium: the check above would fail
// for a model that ignored the in-situ state of the joints. Here the tets are prestressed but the faces
// carry no in-situ traction, so the block must move.
TEST(InSituStress, UnbalancedBoundaryLaunchesAWave) {
  Scene scene = validation_scene("in_situ_block.yaml");
  scene.solid->boundaries.clear();
  double largest_speed = 0.0;
  run_watching(scene, 1, [&](Simulation& sim) {
    for (double c : sim.world().store.table("solid_node").span<const double>("v"))
      largest_speed = std::max(largest_speed, std::abs(c));
  });
  EXPECT_GT(largest_speed, 0.01);
}

// A step 3 x the stable estimate, allowed on purpose (the estimate is a Gershgorin-type lower bound:
// on this bar 2 x still ran its 200 steps; 3 x inverts a tet within 20 steps): the run must stop with a
// diagnosis naming the step, the cause and the remedy, before any field turns into NaN.
TEST(RuntimeGuard, UnstableStepStopsWithADiagnosis) {
  Scene probe = validation_scene("wave_bar.yaml");
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  const double stable = Simulation(probe, o).world().stable_dt();
  Scene scene = validation_scene(
      "wave_bar.yaml", {"time.dt=" + fmt::format("{:.17g}", 3.0 * stable), "time.allow_unstable_dt=true"});
  Simulation sim(scene, o);
  try {
    while (sim.step() < sim.total_steps()) sim.step_once();
    FAIL() << "the unstable run finished";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("step"), std::string::npos) << what;
    EXPECT_NE(what.find("What to change"), std::string::npos) << what;
    EXPECT_NE(what.find("time.dt"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace rift::validation
