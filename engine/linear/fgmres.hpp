#pragma once
// Right-preconditioned flexible GMRES(m) (Saad 1993, "A flexible inner-outer preconditioned GMRES
// algorithm"): solves A x = b for an operator and a preconditioner given as callables, where the
// preconditioner may change from one iteration to the next (an inner iterative solve, as the fluid's
// pressure Schur complement uses). The workspace is sized once (resize) so solve allocates nothing.
//
//   apply(v, w):        w = A v
//   precondition(r, z): z ~ M^-1 r
//
// x must be zero on entry (the first residual is b). Converged when the residual ||b - A x||_2 (the
// Arnoldi estimate within a cycle, the true one at each restart) is at most `target`; otherwise it stops
// after max_iterations applications of the operator within cycles and says so (converged = false).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "engine/linear/krylov.hpp"

namespace rift {

class Fgmres {
 public:
  // n unknowns, restart length m (at least 1).
  void resize(size_t n, int m) {
    n_ = n;
    m_ = std::max(m, 1);
    v_.assign(static_cast<size_t>(m_ + 1) * n, 0.0);
    z_.assign(static_cast<size_t>(m_) * n, 0.0);
    h_.assign(static_cast<size_t>(m_ + 1) * static_cast<size_t>(m_), 0.0);
    for (auto* w : {&g_, &cs_, &sn_, &y_}) w->assign(static_cast<size_t>(m_) + 1, 0.0);
  }
  int restart() const { return m_; }

  template <class Apply, class Precondition>
  KrylovResult solve(Apply&& apply, Precondition&& precondition, std::span<const double> b,
                     std::span<double> x, double target, int max_iterations) {
    const size_t n = n_;
    const int m = m_;
    KrylovResult res;
    double beta = std::sqrt(dot(b.data(), b.data()));
    res.residual = beta;
    res.converged = beta <= target;
    if (res.converged) return res;
    std::copy(b.begin(), b.end(), v_.begin());  // r = b - A 0
    while (res.iterations < max_iterations) {
      double* v0 = v_.data();
      for (size_t i = 0; i < n; ++i) v0[i] /= beta;
      std::fill(g_.begin(), g_.end(), 0.0);
      g_[0] = beta;
      int j = 0;
      for (; j < m && res.iterations < max_iterations; ++j) {
        ++res.iterations;
        double* vj = v_.data() + static_cast<size_t>(j) * n;
        double* zj = z_.data() + static_cast<size_t>(j) * n;
        double* w = v_.data() + static_cast<size_t>(j + 1) * n;
        precondition(std::span<const double>(vj, n), std::span<double>(zj, n));
        apply(std::span<const double>(zj, n), std::span<double>(w, n));
        const double hn = orthogonalise(j, w);
        rotate(j);
        res.residual = std::abs(g_[static_cast<size_t>(j) + 1]);
        if (res.residual <= target || hn == 0.0) {
          ++j;
          break;
        }
      }
      update(j, x);
      if (res.residual <= target) break;
      // Restart from the true residual r = b - A x.
      apply(std::span<const double>(x.data(), n), std::span<double>(v_.data(), n));
      for (size_t q = 0; q < n; ++q) v_[q] = b[q] - v_[q];
      beta = std::sqrt(dot(v_.data(), v_.data()));
      res.residual = beta;
      if (beta <= target) break;
    }
    res.converged = res.residual <= target;
    return res;
  }

 private:
  double dot(const double* a, const double* c) const {
    double s = 0.0;
    for (size_t i = 0; i < n_; ++i) s += a[i] * c[i];
    return s;
  }
  double& h(int i, int j) {
    return h_[static_cast<size_t>(i) * static_cast<size_t>(m_) + static_cast<size_t>(j)];
  }

  // Modified Gram-Schmidt of w against v_0 .. v_j into column j of H; w normalised. Returns ||w|| before.
  double orthogonalise(int j, double* w) {
    for (int i = 0; i <= j; ++i) {
      const double* vi = v_.data() + static_cast<size_t>(i) * n_;
      const double hij = dot(w, vi);
      h(i, j) = hij;
      for (size_t q = 0; q < n_; ++q) w[q] -= hij * vi[q];
    }
    const double hn = std::sqrt(dot(w, w));
    h(j + 1, j) = hn;
    if (hn > 0.0)
      for (size_t q = 0; q < n_; ++q) w[q] /= hn;
    return hn;
  }

  // The earlier Givens rotations on column j, then the new one that zeroes H(j + 1, j), applied to g.
  void rotate(int j) {
    for (int i = 0; i < j; ++i) {
      const double a = h(i, j), c = h(i + 1, j);
      h(i, j) = cs_[i] * a + sn_[i] * c;
      h(i + 1, j) = -sn_[i] * a + cs_[i] * c;
    }
    const double a = h(j, j), c = h(j + 1, j);
    const double r = std::hypot(a, c);
    cs_[j] = r > 0.0 ? a / r : 1.0;
    sn_[j] = r > 0.0 ? c / r : 0.0;
    h(j, j) = r;
    h(j + 1, j) = 0.0;
    g_[j + 1] = -sn_[j] * g_[j];
    g_[j] = cs_[j] * g_[j];
  }

  // x += Z y with H y = g (upper triangular, j x j).
  void update(int j, std::span<double> x) {
    for (int i = j - 1; i >= 0; --i) {
      double sum = g_[i];
      for (int k = i + 1; k < j; ++k) sum -= h(i, k) * y_[k];
      y_[i] = sum / h(i, i);
    }
    for (int i = 0; i < j; ++i) {
      const double* zi = z_.data() + static_cast<size_t>(i) * n_;
      for (size_t q = 0; q < n_; ++q) x[q] += y_[i] * zi[q];
    }
  }

  size_t n_ = 0;
  int m_ = 1;
  std::vector<double> v_, z_, h_, g_, cs_, sn_, y_;  // basis (m + 1), preconditioned basis (m), Hessenberg
};

}  // namespace rift
