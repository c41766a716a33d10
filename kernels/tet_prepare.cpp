#include <cmath>

#include "kernels/tet_forces.hpp"

namespace rift::kernels {

size_t tet_prepare(std::span<const double> x0, std::span<const int32_t> tet_nodes, std::span<double> dm_inv,
                   std::span<double> volume0, size_t begin, size_t end) {
  size_t rejected = 0;
  for (size_t t = begin; t < end; ++t) {
    const double* p[4];
    for (int a = 0; a < 4; ++a) p[a] = &x0[3 * static_cast<size_t>(tet_nodes[4 * t + a])];
    double E[3][3];  // columns are the reference edges X_c - X_0
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) E[i][c] = p[c + 1][i] - p[0][i];
    double C[3][3];  // cofactors: E^-1 = C^T / det
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        C[i][k] = E[i1][k1] * E[i2][k2] - E[i1][k2] * E[i2][k1];
      }
    const double det = E[0][0] * C[0][0] + E[0][1] * C[0][1] + E[0][2] * C[0][2];
    double* d = &dm_inv[9 * t];
    // !(det > 0) also catches NaN coordinates.
    if (!(det > 0.0) || !std::isfinite(det)) {
      ++rejected;
      volume0[t] = 0.0;
      for (int n = 0; n < 9; ++n) d[n] = 0.0;
      continue;
    }
    const double inv_det = 1.0 / det;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) d[3 * r + c] = C[c][r] * inv_det;
    volume0[t] = det / 6.0;
  }
  return rejected;
}

}  // namespace rift::kernels
