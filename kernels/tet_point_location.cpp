#include "kernels/tet_point_location.hpp"

#include <algorithm>

#include "kernels/tet_geometry.hpp"

namespace rift::kernels {

void tet_barycentric(const double c[4][3], const double* q, double lambda[4]) {
  // lambda_{s+1} = grad N_{s+1} . (q - x_0), the gradients being the rows of J^-1 (tet_geometry.hpp).
  double e[3][3], rows[3][3], r[3];
  tet_edges(c, e);
  for (int d = 0; d < 3; ++d) r[d] = q[d] - c[0][d];
  const double det = tet_inverse_rows(e, rows);
  for (int s = 0; s < 3; ++s) lambda[s + 1] = dot(rows[s], r) / det;
  lambda[0] = 1.0 - lambda[1] - lambda[2] - lambda[3];
}

TetPointLocation locate_in_tets(const double q[3], std::span<const double> x,
                                std::span<const int32_t> tet_nodes, double slack) {
  TetPointLocation best;
  const size_t n_tets = tet_nodes.size() / 4;
  for (size_t t = 0; t < n_tets; ++t) {
    double c[4][3];
    bool misses = false;
    for (int d = 0; d < 3 && !misses; ++d) {
      double lo = 1e300, hi = -1e300;
      for (int a = 0; a < 4; ++a) {
        c[a][d] = x[3 * static_cast<size_t>(tet_nodes[4 * t + a]) + d];
        lo = std::min(lo, c[a][d]);
        hi = std::max(hi, c[a][d]);
      }
      misses = q[d] < lo - slack || q[d] > hi + slack;
    }
    if (misses) continue;
    double lambda[4];
    tet_barycentric(c, q, lambda);
    const double lowest = std::min(std::min(lambda[0], lambda[1]), std::min(lambda[2], lambda[3]));
    if (lowest > best.lowest) {
      best.tet = static_cast<int32_t>(t);
      best.lowest = lowest;
      std::copy(lambda, lambda + 4, best.lambda);
      if (lowest >= 0.0) break;  // inside: no later tet can do better than the first that contains q
    }
  }
  return best;
}

double interpolate_p1(const TetPointLocation& where, std::span<const int32_t> tet_nodes,
                      std::span<const double> field, size_t stride, size_t component) {
  double value = 0.0;
  for (int a = 0; a < 4; ++a)
    value +=
        where.lambda[a] *
        field[stride * static_cast<size_t>(tet_nodes[4 * static_cast<size_t>(where.tet) + a]) + component];
  return value;
}

}  // namespace rift::kernels
