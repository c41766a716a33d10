// The concurrent coupling against the sequential one (docs/coupling.md), on a number nobody chose: the
// order of the difference they make. The concurrent fluid step of a window sees the solid at the window's
// start, the sequential one at its end, so the two differ only by when the solid is sampled, one fluid step
// dt_f apart. Both are consistent exchanges of the same model, so that difference must vanish like dt_f to
// the first power: dz_concurrent - dz_sequential = C dt_f + O(dt_f^2) for the block's displacement dz at a
// fixed time. The observed order is log2 of the ratio of differences at dt_f and dt_f / 2.
//
// The case is the density-ratio-10 block of scenes/validation/immersed_block.yaml sinking from rest for
// 0.02 s (test_fluid_solid_stability.cpp runs it longer). The solid's step follows fluid.dt (automatic
// sub-steps), the same in both couplings at each level, so the difference isolates the sampling time.
//
// Measured (2 threads, bitwise the same on any count): the difference concurrent - sequential in the drop
// is -4.394e-5, -4.289e-5, -3.027e-5, -1.815e-5 m at fluid.dt = 5, 2.5, 1.25, 0.625 ms, observed orders
// 0.03, 0.50, 0.74: the order rises towards 1 as the step shrinks, the coarse steps are not yet in the
// asymptotic range (at 5 ms a window is a quarter of the 20 ms run, and each coupling's own drop still
// moves by 5 % per halving). The levels below are therefore 2.5, 1.25 and 0.625 ms, and the test asserts
// the finer pair's order in [0.7, 1.5] (the bound was fixed before measuring, from the claim: an order
// below 0.7 would mean the difference does not vanish like a lag, above 1.5 that it is a second-order
// effect) and that the order still rises (the approach to 1 from below). The finer pair passes by a slim
// margin (0.74); the next level (0.3125 ms, 128 fluid steps) was not run: too slow for this suite.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "systems/solid_tables.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift::validation {
namespace {

// The block's mass-weighted mean drop after 0.02 s.
double drop(const char* coupling, double fluid_dt) {
  Scene scene = validation_scene("immersed_block.yaml", {"solid.materials[0].density=10000", "time.end=0.02",
                                                         std::string("fluid_solid.coupling=") + coupling,
                                                         fmt::format("fluid.dt={:.17g}", fluid_dt)});
  double z0 = 0.0, z = 0.0;
  bool first = true;
  run_watching(scene, 2, [&](Simulation& sim) {
    const Table& nodes = sim.world().store.table(solid::node_table);
    const auto x = nodes.span<double>("x");
    const auto m = nodes.span<double>("mass");
    double mz = 0.0, mass = 0.0;
    for (size_t n = 0; n < nodes.size(); ++n) {
      mz += m[n] * x[3 * n + 2];
      mass += m[n];
    }
    z = mz / mass;
    if (first) z0 = z, first = false;
  });
  return z - z0;
}

TEST(FluidSolidConcurrentLag, TheDifferenceFromSequentialIsFirstOrderInTheFluidStep) {
  const double dts[] = {0.0025, 0.00125, 0.000625};
  double diff[3];
  for (int i = 0; i < 3; ++i) {
    const double seq = drop("sequential", dts[i]);
    const double conc = drop("concurrent", dts[i]);
    diff[i] = conc - seq;
    std::printf("fluid.dt = %.5g s: drop sequential %.9g m, concurrent %.9g m, difference %.4g m\n", dts[i],
                seq, conc, diff[i]);
    ASSERT_LT(seq, 0.0);  // it sinks
    ASSERT_LT(conc, 0.0);
  }
  const double coarse_order = std::log2(std::abs(diff[0] / diff[1]));
  const double fine_order = std::log2(std::abs(diff[1] / diff[2]));
  std::printf("observed order: %.3f (2.5 -> 1.25 ms), %.3f (1.25 -> 0.625 ms)\n", coarse_order, fine_order);
  EXPECT_GT(std::abs(diff[2]), 0.0);
  // A leading term C dt_f keeps its sign as dt_f shrinks.
  EXPECT_EQ(std::signbit(diff[0]), std::signbit(diff[1]));
  EXPECT_EQ(std::signbit(diff[1]), std::signbit(diff[2]));
  EXPECT_GE(fine_order, 0.7);
  EXPECT_LE(fine_order, 1.5);
  EXPECT_GT(fine_order, coarse_order);
}

}  // namespace
}  // namespace rift::validation
