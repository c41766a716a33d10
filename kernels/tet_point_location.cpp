#include "kernels/tet_point_location.hpp"

#include <algorithm>

namespace rift::kernels {

void tet_barycentric(const double c[4][3], const double* q, double lambda[4]) {
  double e[3][3], r[3];
  for (int d = 0; d < 3; ++d) {
    for (int a = 0; a < 3; ++a) e[a][d] = c[a + 1][d] - c[0][d];
    r[d] = q[d] - c[0][d];
  }
  auto det3 = [](const double u[3], const double v[3], const double w[3]) {
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
  };
  const double det = det3(e[0], e[1], e[2]);
  lambda[1] = det3(r, e[1], e[2]) / det;
  lambda[2] = det3(e[0], r, e[2]) / det;
  lambda[3] = det3(e[0], e[1], r) / det;
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
