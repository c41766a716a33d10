// The dynamic pressure subscale's kernels (kernels/fluid_subscale.hpp) on one tet:
//  - its fixed point under a constant residual is the quasi-static subscale -tau (grad p - xibar), reached
//    at the rate tau_t rho/dt per step (so the steady state does not depend on dt);
//  - its explicit continuity term sums to zero over the tet's nodes (sum of shape gradients = 0): it moves
//    no net volume, so a closed domain's compatibility holds.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "kernels/fluid_subscale.hpp"

namespace rift::kernels {
namespace {

struct UnitTet {
  std::vector<int32_t> nodes{0, 1, 2, 3};
  std::vector<double> volume{1.0 / 6.0};
  // Shape gradients of the tet (0,0,0), (1,0,0), (0,1,0), (0,0,1).
  std::vector<double> grad{-1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1};
};

TEST(PressureSubscale, ItsFixedPointIsTheQuasiStaticSubscaleWhateverDt) {
  const UnitTet t;
  // p = 3x - 2y + 5z + 1 with a projected gradient xi = (1, 1, 1) at every node: grad p - xibar = (2, -3, 4).
  const std::vector<double> p{1.0, 4.0, -1.0, 6.0};
  const std::vector<double> xi(12, 1.0);
  const double tau = 0.02, rho = 1000.0;
  for (const double dt : {2.0, 20.0, 200.0}) {  // r = 0.91, 0.5, 0.09 (rho tau = 20 s)
    const double tau_t = 1.0 / (rho / dt + 1.0 / tau);
    const std::vector<double> tau_ts{tau_t};
    const PressureSubscaleArgs a{t.nodes, t.volume, t.grad, tau_ts, rho / dt};
    std::vector<double> u(3, 0.0);
    // One step from zero: -tau_t (grad p - xibar), exactly.
    pressure_subscale_update(a, p, xi, u);
    EXPECT_DOUBLE_EQ(u[0], -tau_t * 2.0);
    EXPECT_DOUBLE_EQ(u[1], tau_t * 3.0);
    // Many steps: -tau (grad p - xibar). The error contracts by r = tau_t rho/dt per step.
    const double r = tau_t * rho / dt;
    const int steps = static_cast<int>(std::ceil(std::log(1e-13) / std::log(r))) + 1;
    for (int k = 1; k < steps; ++k) pressure_subscale_update(a, p, xi, u);
    EXPECT_NEAR(u[0], -tau * 2.0, 1e-12 * tau * 4.0) << dt;
    EXPECT_NEAR(u[1], tau * 3.0, 1e-12 * tau * 4.0) << dt;
    EXPECT_NEAR(u[2], -tau * 4.0, 1e-12 * tau * 4.0) << dt;
  }
}

TEST(PressureSubscale, ItsContinuityTermMovesNoNetVolume) {
  const UnitTet t;
  const std::vector<double> tau_ts{0.5};
  const PressureSubscaleArgs a{t.nodes, t.volume, t.grad, tau_ts, 2.0};
  const std::vector<double> u{0.3, -0.7, 1.1};
  std::vector<double> rhs(4, 0.0);
  pressure_subscale_rhs(a, u, rhs);
  // Node 1's shape gradient is (1, 0, 0): tau_t rho/dt V g_1 . u' = 0.5 x 2 x 1/6 x 0.3.
  EXPECT_DOUBLE_EQ(rhs[1], 0.5 * 2.0 / 6.0 * 0.3);
  EXPECT_NEAR(rhs[0] + rhs[1] + rhs[2] + rhs[3], 0.0, 1e-15);
}

}  // namespace
}  // namespace rift::kernels
