#pragma once
// Jacobi-preconditioned BiCGSTAB (van der Vorst 1992) on a CsrMatrix, for the non-symmetric velocity
// (momentum) systems. Work vectors are sized once (resize) so solve allocates nothing. Converged when
// ||b - A x||_2 <= max(rel_tol ||b||_2, abs_tol, initial_rel_tol ||b - A x_0||_2) (the last one is the
// forcing term of an inexact outer iteration: reduce the residual of the initial guess by that factor).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/linear/csr_matrix.hpp"

namespace rift {

struct KrylovResult {
  int iterations = 0;
  double residual = 0.0;  // final ||b - A x||_2
  bool converged = false;
};

class BicgstabJacobi {
 public:
  void resize(int32_t n);
  // x holds the initial guess on entry.
  KrylovResult solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x, double rel_tol,
                     double abs_tol, int max_iterations, double initial_rel_tol = 0.0);

 private:
  std::vector<double> inv_diag_, r_, r0_, p_, v_, s_, t_, y_, z_;
};

}  // namespace rift
