// Stability at the extremes, coupling side (issue 7): the solid/fluid density ratio from 0.1 to 10, on the
// free block of scenes/validation/immersed_block.yaml (a 0.2 m block in a closed 1 m box of fluid at rest,
// under gravity). Each case runs stably with bounded energy, or stops with a diagnosis that names the
// cause and what to change (docs/stability.md):
//   - ratio 10: the block sinks; ratio 0.1 with fluid_solid.added_mass: 1: it rises;
//   - ratio 0.1 without it: the staggered exchange's added-mass instability, stopped with its diagnosis.
// Bounded energy: the box is closed and gravity is the only source, so the kinetic energy of solid and fluid
// cannot exceed the potential energy released, |m_s - rho_f V| g |dz| (dz: the block's drop or rise). The
// fluid's kinetic energy includes the fictitious fluid inside the block, which moves with it: that
// 1/2 rho_f V U^2 is taken off (without it the sum may exceed the bound by exactly that much).
#include <gtest/gtest.h>

#include <cmath>

#include "systems/fluid/fluid_model.hpp"
#include "systems/solid_tables.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift::validation {
namespace {

constexpr double kRhoFluid = 1000.0, kG = 9.81, kVolume = 0.008;  // the scene's

struct BlockState {
  double z = 0.0, vz = 0.0;  // mean node height and vertical velocity (nodes carry equal shares of mass)
};

BlockState block_state(Simulation& sim) {
  const Table& nodes = sim.world().store.table(solid::node_table);
  const auto x = nodes.span<double>("x");
  const auto v = nodes.span<double>("v");
  const auto m = nodes.span<double>("mass");
  BlockState s;
  double mass = 0.0;
  for (size_t n = 0; n < nodes.size(); ++n) {
    s.z += m[n] * x[3 * n + 2];
    s.vz += m[n] * v[3 * n + 2];
    mass += m[n];
  }
  s.z /= mass;
  s.vz /= mass;
  return s;
}

FluidModel& fluid_of(Simulation& sim) {
  for (auto& m : sim.world().models)
    if (auto* f = dynamic_cast<FluidModel*>(m.get())) return *f;
  throw std::runtime_error("the scene has no fluid");
}

struct Outcome {
  BlockState start, end;
  double max_excess = -1e300;  // max over steps of (kinetic energy - released potential energy) [J]
  double released = 0.0;       // at the end [J]
  double kinetic = 0.0;        // at the end [J]
  bool finite = true;
};

Outcome run_block(double solid_density, double added_mass, double end_time) {
  Scene scene =
      validation_scene("immersed_block.yaml", {"solid.materials[0].density=" + std::to_string(solid_density),
                                               "fluid_solid.added_mass=" + std::to_string(added_mass),
                                               "time.end=" + std::to_string(end_time)});
  const double net_weight = std::abs(solid_density - kRhoFluid) * kVolume * kG;
  Outcome o;
  bool first = true;
  run_watching(scene, 2, [&](Simulation& sim) {
    const BlockState s = block_state(sim);
    if (first) o.start = s, first = false;
    o.end = s;
    SolidModel& solid = solid_of(sim);
    Metrics m(solid);
    m.update(sim.time());
    // The solid's kinetic energy without the virtual mass the coupling may have added (it is not physical).
    const double physical_ke =
        m["solid_kinetic_energy"] * solid_density / (solid_density + added_mass * kRhoFluid);
    const double fluid_ke = fluid_of(sim).kinetic_energy() - 0.5 * kRhoFluid * kVolume * s.vz * s.vz;
    o.released = net_weight * std::abs(s.z - o.start.z);
    o.kinetic = physical_ke + fluid_ke;
    o.max_excess = std::max(o.max_excess, o.kinetic - o.released);
    o.finite = o.finite && std::isfinite(s.z) && std::isfinite(physical_ke + fluid_ke);
  });
  return o;
}

TEST(FluidSolidDensityRatio, TenTimesTheFluidSinksWithBoundedEnergy) {
  const Outcome o = run_block(10000.0, 0.0, 0.05);
  ASSERT_TRUE(o.finite);
  EXPECT_LT(o.end.vz, 0.0);
  EXPECT_LT(o.end.z, o.start.z);
  std::printf("ratio 10: dz = %.4g m, vz = %.4g m/s, kinetic %.4g J of %.4g J released, max excess %.3g J\n",
              o.end.z - o.start.z, o.end.vz, o.kinetic, o.released, o.max_excess);
  EXPECT_LE(o.max_excess, 0.0);
}

TEST(FluidSolidDensityRatio, ATenthOfTheFluidRisesWithTheAddedMass) {
  const Outcome o = run_block(100.0, 1.0, 0.05);
  ASSERT_TRUE(o.finite);
  EXPECT_GT(o.end.vz, 0.0);
  EXPECT_GT(o.end.z, o.start.z);
  std::printf(
      "ratio 0.1, added mass 1: dz = %.4g m, vz = %.4g m/s, kinetic %.4g J of %.4g J released, max "
      "excess %.3g J\n",
      o.end.z - o.start.z, o.end.vz, o.kinetic, o.released, o.max_excess);
  EXPECT_LE(o.max_excess, 0.0);
}

TEST(FluidSolidDensityRatio, ATenthOfTheFluidWithoutTheAddedMassStopsWithTheDiagnosis) {
  try {
    run_block(100.0, 0.0, 0.05);
    FAIL() << "expected the added-mass instability to stop the run";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("added-mass instability"), std::string::npos) << what;
    EXPECT_NE(what.find("fluid_solid.added_mass: 1"), std::string::npos) << what;
    EXPECT_NE(what.find("0.1 times the fluid's"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace rift::validation
