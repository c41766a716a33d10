#pragma once
// Right-preconditioned flexible GMRES(m) (Saad 1993, "A flexible inner-outer preconditioned GMRES
// algorithm"): solves A x = b for an operator and a preconditioner given as callables, where the
// preconditioner may change from one iteration to the next (an inner iterative solve, as the fluid's
// pressure Schur complement uses). The basis vectors are allocated the first time a cycle reaches them and
// kept: a long restart costs memory only where a solve needs its depth, and once a run's solves have
// reached their depth, solve allocates nothing.
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
    v_.clear();
    z_.clear();
    // Reserved so that pointers into earlier vectors stay valid while the basis grows.
    v_.reserve(static_cast<size_t>(m_) + 1);
    z_.reserve(static_cast<size_t>(m_));
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
    std::copy(b.begin(), b.end(), basis(v_, 0));  // r = b - A 0
    while (res.iterations < max_iterations) {
      double* v0 = basis(v_, 0);
      for (size_t i = 0; i < n; ++i) v0[i] /= beta;
      std::fill(g_.begin(), g_.end(), 0.0);
      g_[0] = beta;
      int j = 0;
      for (; j < m && res.iterations < max_iterations; ++j) {
        ++res.iterations;
        double* vj = basis(v_, j);
        double* zj = basis(z_, j);
        double* w = basis(v_, j + 1);
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
      double* r = basis(v_, 0);
      apply(std::span<const double>(x.data(), n), std::span<double>(r, n));
      for (size_t q = 0; q < n; ++q) r[q] = b[q] - r[q];
      beta = std::sqrt(dot(r, r));
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
  // Vector i of a basis (n values), allocated on first use.
  double* basis(std::vector<std::vector<double>>& vs, int i) {
    const auto k = static_cast<size_t>(i);
    if (vs.size() <= k) vs.resize(k + 1);
    if (vs[k].size() != n_) vs[k].assign(n_, 0.0);
    return vs[k].data();
  }
  double& h(int i, int j) {
    return h_[static_cast<size_t>(i) * static_cast<size_t>(m_) + static_cast<size_t>(j)];
  }

  // Modified Gram-Schmidt of w against v_0 .. v_j into column j of H; w normalised. Returns ||w|| before.
  double orthogonalise(int j, double* w) {
    for (int i = 0; i <= j; ++i) {
      const double* vi = v_[static_cast<size_t>(i)].data();
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
      const double* zi = z_[static_cast<size_t>(i)].data();
      for (size_t q = 0; q < n_; ++q) x[q] += y_[i] * zi[q];
    }
  }

  size_t n_ = 0;
  int m_ = 1;
  std::vector<std::vector<double>> v_, z_;   // basis (up to m + 1), preconditioned basis (up to m)
  std::vector<double> h_, g_, cs_, sn_, y_;  // Hessenberg (m + 1) x m, rotations, right-hand side
};

}  // namespace rift
