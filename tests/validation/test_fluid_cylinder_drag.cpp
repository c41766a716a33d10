// Drag on an immersed cylinder at Re = 20 against Schäfer & Turek's benchmark 2D-1 (issue 24): a number
// nobody here chose. tests/validation/schafer_turek.hpp has the case, the meshes, the immersion (the
// cylinder is not in the fluid mesh: exact volume fraction and absorption, as test_fluid_immersed_drag)
// and the reference values with their source.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "tests/validation/schafer_turek.hpp"

namespace rift {
namespace {

using fluid_test::kTurekDeltaP;
using fluid_test::kTurekDrag;
using fluid_test::kTurekLift;
using fluid_test::run_turek_2d1;
using fluid_test::TurekResult;

// Measured (h the cell size at the cylinder; 11,664, 25,392 and 58,776 fluid tets; ~27 s in all):
//   h = D/10: c_D 6.3135 (+13.2 %), c_L -0.261, delta p 0.0979
//   h = D/20: c_D 5.9254 (+6.2 %),  c_L -0.136, delta p 0.1047
//   h = D/40: c_D 5.7313 (+2.7 %),  c_L -0.054, delta p 0.1107
// The differences of c_D halve with h (observed order 1.00): first order, as the Stokes sphere, the
// interface smeared over one cell. Asserted: the observed order p = log2((c1 - c2) / (c2 - c3)), which
// needs no reference, in [0.7, 1.3]; and the first-order Richardson limit 2 c3 - c2 (measured 5.537,
// -0.8 %) within 2 % of 5.5795. Why 2 %: the limit still carries what does not shrink with h here, the
// penalty's finite sigma0 (about -0.2 %, schafer_turek.hpp) and the far field, whose cells (growth 1.15,
// up to 0.04) do not halve with h (a finer far field, growth 1.08 up to 0.02: c_D 5.8926 and 5.7205 at
// D/20 and D/40, limit 5.548, -0.56 %: the far field moves the limit by 0.2 %); and the Richardson limit's
// own error, the next order's term. 2 % is ten times the paper's band (5.57 - 5.59) and below the finest
// mesh's own error, so it does check the extrapolation. Lift and the pressure difference are printed, not
// asserted: c_L (0.0106) is 0.2 % of c_D and below this discretisation's error at these meshes (the Kuhn
// lattice's diagonals are not symmetric about y = 0.2); delta p is read at the surface, inside the smeared
// interface, and converges slowly (0.098, 0.105, 0.111 against 0.1175).
TEST(FluidCylinderDrag, SchaeferTurek2D1DragConvergesAtFirstOrder) {
  const TurekResult coarse = run_turek_2d1(0.1 / 10);
  const TurekResult medium = run_turek_2d1(0.1 / 20);
  const TurekResult fine = run_turek_2d1(0.1 / 40);
  // The ring's polygons have the circles' areas, and the fluid sees all of it (exact clipping).
  const double ring_area = std::numbers::pi * 0.25 * 0.1 * 0.1 * (1 - 0.75 * 0.75);
  for (const TurekResult* r : {&coarse, &medium, &fine}) {
    EXPECT_TRUE(r->converged);
    EXPECT_NEAR(r->solid_area / ring_area, 1.0, 1e-9);
  }
  ASSERT_GT(coarse.drag, medium.drag);
  ASSERT_GT(medium.drag, fine.drag);
  const double order = std::log2((coarse.drag - medium.drag) / (medium.drag - fine.drag));
  const double limit = 2.0 * fine.drag - medium.drag;
  std::printf(
      "observed order %.2f; Richardson limit c_D %.4f (%+.2f %% of %.4f); c_L %.4f -> %.4f (ref %.4f), "
      "delta p %.4f -> %.4f (ref %.4f)\n",
      order, limit, 100 * (limit / kTurekDrag - 1), kTurekDrag, fine.lift, 2 * fine.lift - medium.lift,
      kTurekLift, fine.delta_p, 2 * fine.delta_p - medium.delta_p, kTurekDeltaP);
  EXPECT_GE(order, 0.7);
  EXPECT_LE(order, 1.3);
  EXPECT_LE(std::abs(limit / kTurekDrag - 1), 0.02);
}

}  // namespace
}  // namespace rift
