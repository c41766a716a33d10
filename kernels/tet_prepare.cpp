#include <cmath>

#include "kernels/tet_forces.hpp"
#include "kernels/tet_geometry.hpp"

namespace rift::kernels {

size_t tet_prepare(std::span<const double> x0, std::span<const int32_t> tet_nodes, std::span<double> dm_inv,
                   std::span<double> volume0, size_t begin, size_t end) {
  size_t rejected = 0;
  for (size_t t = begin; t < end; ++t) {
    const double* p[4];
    for (int a = 0; a < 4; ++a) p[a] = &x0[3 * static_cast<size_t>(tet_nodes[4 * t + a])];
    double e[3][3], rows[3][3];  // J = [e_0 e_1 e_2]; Dm^-1 = J^-1, whose rows are rows / det
    tet_edges(p, e);
    const double det = tet_inverse_rows(e, rows);
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
      for (int c = 0; c < 3; ++c) d[3 * r + c] = rows[r][c] * inv_det;
    volume0[t] = det / 6.0;
  }
  return rejected;
}

}  // namespace rift::kernels
