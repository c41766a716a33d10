#include "engine/linear/krylov.hpp"

#include <algorithm>
#include <cmath>

namespace rift {

namespace {

double dot(std::span<const double> a, std::span<const double> b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace

void BicgstabJacobi::resize(int32_t n) {
  for (auto* v : {&inv_diag_, &r_, &r0_, &p_, &v_, &s_, &t_, &y_, &z_})
    v->assign(static_cast<size_t>(n), 0.0);
}

KrylovResult BicgstabJacobi::solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x,
                                   double rel_tol, double abs_tol, int max_iterations,
                                   double initial_rel_tol) {
  const size_t n = static_cast<size_t>(a.rows);
  if (r_.size() != n) resize(a.rows);
  for (int32_t i = 0; i < a.rows; ++i) {
    double d = 0.0;
    for (int32_t k = a.row_ptr[i]; k < a.row_ptr[i + 1]; ++k)
      if (a.col[k] == i) d = a.val[k];
    inv_diag_[i] = d != 0.0 ? 1.0 / d : 1.0;
  }
  a.multiply(x, r_);
  for (size_t i = 0; i < n; ++i) r_[i] = b[i] - r_[i];
  KrylovResult res;
  res.residual = std::sqrt(dot(r_, r_));
  const double target = std::max({rel_tol * std::sqrt(dot(b, b)), abs_tol, initial_rel_tol * res.residual});
  if (res.residual <= target) {
    res.converged = true;
    return res;
  }
  r0_ = r_;
  double rho = 1.0, alpha = 1.0, omega = 1.0;
  std::fill(p_.begin(), p_.end(), 0.0);
  std::fill(v_.begin(), v_.end(), 0.0);
  for (int it = 1; it <= max_iterations; ++it) {
    const double rho_new = dot(r0_, r_);
    if (rho_new == 0.0) break;
    const double beta = (rho_new / rho) * (alpha / omega);
    rho = rho_new;
    for (size_t i = 0; i < n; ++i) p_[i] = r_[i] + beta * (p_[i] - omega * v_[i]);
    for (size_t i = 0; i < n; ++i) y_[i] = inv_diag_[i] * p_[i];
    a.multiply(y_, v_);
    const double r0v = dot(r0_, v_);
    if (r0v == 0.0) break;
    alpha = rho / r0v;
    for (size_t i = 0; i < n; ++i) s_[i] = r_[i] - alpha * v_[i];
    res.iterations = it;
    if (std::sqrt(dot(s_, s_)) <= target) {
      for (size_t i = 0; i < n; ++i) x[i] += alpha * y_[i];
      res.residual = std::sqrt(dot(s_, s_));
      res.converged = true;
      return res;
    }
    for (size_t i = 0; i < n; ++i) z_[i] = inv_diag_[i] * s_[i];
    a.multiply(z_, t_);
    const double tt = dot(t_, t_);
    omega = tt > 0.0 ? dot(t_, s_) / tt : 0.0;
    for (size_t i = 0; i < n; ++i) {
      x[i] += alpha * y_[i] + omega * z_[i];
      r_[i] = s_[i] - omega * t_[i];
    }
    res.residual = std::sqrt(dot(r_, r_));
    if (res.residual <= target) {
      res.converged = true;
      return res;
    }
    if (omega == 0.0) break;
  }
  return res;
}

}  // namespace rift
