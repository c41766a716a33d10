// Flexible GMRES (engine/linear/fgmres.hpp) on small non-symmetric systems against a dense LU solve.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <span>
#include <vector>

#include "engine/linear/fgmres.hpp"

namespace rift {
namespace {

// Upwinded 1D convection-diffusion, -u'' + Pe u' on n nodes: non-symmetric, diagonally dominant.
Eigen::MatrixXd convection_diffusion(int n, double peclet) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 2.0 + peclet;
    if (i > 0) a(i, i - 1) = -1.0 - peclet;
    if (i + 1 < n) a(i, i + 1) = -1.0;
  }
  return a;
}

struct Problem {
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  explicit Problem(int n) : a(convection_diffusion(n, 4.0)), b(n) {
    for (int i = 0; i < n; ++i) b(i) = std::sin(0.3 * i) + 0.1 * i;
  }
  auto apply() const {
    return [this](std::span<const double> v, std::span<double> w) {
      Eigen::Map<Eigen::VectorXd>(w.data(), long(w.size())) =
          a * Eigen::Map<const Eigen::VectorXd>(v.data(), long(v.size()));
    };
  }
  double residual(const std::vector<double>& x) const {
    return (b - a * Eigen::Map<const Eigen::VectorXd>(x.data(), long(x.size()))).norm();
  }
};

TEST(Fgmres, SolvesANonSymmetricSystemWithRestarts) {
  const int n = 60;
  const Problem p(n);
  Fgmres solver;
  solver.resize(n, 8);  // restarts: 8 < n
  std::vector<double> x(n, 0.0);
  const double target = 1e-10 * p.b.norm();
  const auto jacobi = [&](std::span<const double> r, std::span<double> z) {
    for (int i = 0; i < n; ++i) z[i] = r[i] / p.a(i, i);
  };
  const KrylovResult r =
      solver.solve(p.apply(), jacobi, std::span<const double>(p.b.data(), n), x, target, 2000);
  EXPECT_TRUE(r.converged);
  EXPECT_GT(r.iterations, 8);  // it needed at least one restart
  // The reported residual is the true one at the last restart or the Arnoldi estimate: both within a
  // factor of round-off of the residual recomputed here.
  EXPECT_LE(p.residual(x), 1.01 * target + 1e-14 * p.b.norm());
  const Eigen::VectorXd exact = p.a.partialPivLu().solve(p.b);
  EXPECT_LT((Eigen::Map<const Eigen::VectorXd>(x.data(), n) - exact).norm(), 1e-8 * exact.norm());
}

TEST(Fgmres, AcceptsAPreconditionerThatChangesEveryIteration) {
  // The flexible variant keeps the preconditioned vectors, so an inner solve whose accuracy varies from one
  // call to the next (here Jacobi scaled by a factor cycling in [0.5, 1.5]) still converges.
  const int n = 40;
  const Problem p(n);
  Fgmres solver;
  solver.resize(n, 40);
  std::vector<double> x(n, 0.0);
  int call = 0;
  const auto varying = [&](std::span<const double> r, std::span<double> z) {
    const double f = 1.0 + 0.5 * std::sin(1.7 * call++);
    for (int i = 0; i < n; ++i) z[i] = f * r[i] / p.a(i, i);
  };
  const double target = 1e-9 * p.b.norm();
  const KrylovResult r =
      solver.solve(p.apply(), varying, std::span<const double>(p.b.data(), n), x, target, 200);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(p.residual(x), 1.01 * target + 1e-14 * p.b.norm());
}

TEST(Fgmres, ReportsTheCapAndAZeroRightHandSide) {
  const int n = 30;
  const Problem p(n);
  Fgmres solver;
  solver.resize(n, 10);
  const auto identity = [](std::span<const double> r, std::span<double> z) {
    for (size_t i = 0; i < r.size(); ++i) z[i] = r[i];
  };
  std::vector<double> x(n, 0.0);
  const KrylovResult capped =
      solver.solve(p.apply(), identity, std::span<const double>(p.b.data(), n), x, 1e-14 * p.b.norm(), 3);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.iterations, 3);
  EXPECT_GT(capped.residual, 1e-14 * p.b.norm());
  EXPECT_NEAR(capped.residual, p.residual(x), 1e-9 * p.b.norm());  // a cycle cut short ends with x updated

  const std::vector<double> zero(n, 0.0);
  std::vector<double> y(n, 0.0);
  const KrylovResult none = solver.solve(p.apply(), identity, zero, y, 1e-12, 100);
  EXPECT_TRUE(none.converged);
  EXPECT_EQ(none.iterations, 0);
  for (double v : y) EXPECT_EQ(v, 0.0);
}

}  // namespace
}  // namespace rift
