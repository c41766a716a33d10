// The orthogonal-subscale convection stabilisation (kernels/fluid_convection_subscale.hpp) on one tet:
//  - tau_c has the advective and diffusive limits h / (2|w|) and h^2 / (4 nu), and no dt;
//  - the projection of w . grad w for a linear w is its (constant) cell value at every node;
//  - consistency: for a linear velocity the projected term cancels the streamline operator exactly, so the
//    stabilisation adds nothing where the P1 space represents the convective derivative (plain streamline
//    diffusion adds rho tau V (w . g_a)(w . grad u) there, which is what moved the steady state with dt).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "kernels/fluid_convection_subscale.hpp"
#include "kernels/fluid_element.hpp"

namespace rift::kernels {
namespace {

TEST(ConvectionSubscale, TauHasTheAdvectiveAndDiffusiveLimitsAndNoDt) {
  const double h = 0.1;
  EXPECT_NEAR(convection_subscale_tau(10.0, h, 1e-12, 0.0), h / 20.0, 1e-15);
  EXPECT_NEAR(convection_subscale_tau(1e-12, h, 0.5, 0.0), h * h / 2.0, 1e-15);
  EXPECT_NEAR(convection_subscale_tau(0.0, h, 0.0, 4.0), 0.25, 1e-15);
  EXPECT_EQ(convection_subscale_tau(0.0, h, 0.0, 0.0), 0.0);
}

struct LinearFlow {
  std::vector<double> x{0.1, 0.0, 0.0, 1.2, 0.1, 0.0, 0.2, 0.9, 0.1, 0.0, 0.3, 1.1};  // a skewed tet
  double a[3][3] = {{0.3, -1.2, 0.5}, {0.7, 0.2, -0.4}, {-0.6, 0.9, -0.5}};           // w = a x + b (trace 0)
  double b[3] = {1.0, -0.5, 0.25};
  std::vector<double> w = std::vector<double>(12);
  LinearFlow() {
    for (int n = 0; n < 4; ++n)
      for (int d = 0; d < 3; ++d)
        w[3 * n + d] = b[d] + a[d][0] * x[3 * n] + a[d][1] * x[3 * n + 1] + a[d][2] * x[3 * n + 2];
  }
  // (wbar . grad) w = a wbar, wbar the mean of the corner values.
  std::array<double, 3> convective_derivative() const {
    double wbar[3] = {0.0, 0.0, 0.0};
    for (int n = 0; n < 4; ++n)
      for (int d = 0; d < 3; ++d) wbar[d] += 0.25 * w[3 * n + d];
    std::array<double, 3> c{};
    for (int d = 0; d < 3; ++d) c[d] = a[d][0] * wbar[0] + a[d][1] * wbar[1] + a[d][2] * wbar[2];
    return c;
  }
};

TEST(ConvectionSubscale, TheProjectionOfALinearFlowsDerivativeIsItsCellValue) {
  LinearFlow f;
  std::vector<double> grad(12), volume(1), eta(12, 0.0);
  volume[0] = p1_gradients(f.x.data(), grad.data());
  ASSERT_GT(volume[0], 0.0);
  const std::vector<int32_t> nodes{0, 1, 2, 3};
  convective_derivative_projection(nodes, volume, grad, f.w, eta);
  const auto c = f.convective_derivative();
  for (int n = 0; n < 4; ++n)
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(eta[3 * n + d] / (0.25 * volume[0]), c[d], 1e-13);
}

TEST(ConvectionSubscale, ALinearVelocityGetsNoStabilisation) {
  LinearFlow f;
  std::vector<double> grad(12), volume(1), h(1), eta(12, 0.0);
  const std::vector<int32_t> nodes{0, 1, 2, 3};
  p1_prepare(f.x, nodes, volume, grad, h);
  convective_derivative_projection(nodes, volume, grad, f.w, eta);
  for (double& e : eta) e /= 0.25 * volume[0];
  std::vector<int32_t> slot(16);
  for (int e = 0; e < 16; ++e) slot[e] = e;
  const std::vector<double> p(4, 0.0), tau{0.037};
  const auto assemble = [&](bool projected, std::vector<double>& matrix, std::vector<double>& rhs) {
    FluidMomentumArgs m;
    m.rho = 2.0;
    m.mu = 0.0;
    m.dt = 1.0;
    m.theta = 1.0;
    m.tet_nodes = nodes;
    m.volume = volume;
    m.grad = grad;
    m.slot = slot;
    m.u_old = f.w;
    m.advect = f.w;
    m.pressure = p;
    m.supg_tau = tau;
    if (projected) m.convection_projection = eta;
    m.matrix_values = matrix;
    m.rhs = rhs;
    fluid_assemble_momentum(m);
  };
  std::vector<double> k0(16, 0.0), r0(12, 0.0), k1(16, 0.0), r1(12, 0.0);
  assemble(false, k0, r0);
  assemble(true, k1, r1);
  // The streamline operator applied to u = w: what the projection must give back on the right-hand side.
  double wbar[3] = {0.0, 0.0, 0.0}, s[16];
  for (int n = 0; n < 4; ++n)
    for (int d = 0; d < 3; ++d) wbar[d] += 0.25 * f.w[3 * n + d];
  p1_streamline_diffusion(volume[0], grad.data(), wbar, 2.0 * tau[0], s);
  double scale = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d) {
      double su = 0.0;
      for (int j = 0; j < 4; ++j) su += s[4 * i + j] * f.w[3 * j + d];
      scale = std::max(scale, std::abs(su));
      EXPECT_NEAR(r1[3 * i + d] - r0[3 * i + d], su, 1e-13) << i << " " << d;
    }
  EXPECT_GT(scale, 1e-3);  // the streamline term is not trivially zero here
  for (int e = 0; e < 16; ++e) EXPECT_EQ(k1[e], k0[e]);
}

}  // namespace
}  // namespace rift::kernels
