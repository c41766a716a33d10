#include "kernels/fluid_convection_subscale.hpp"

#include <cmath>

namespace rift::kernels {

double convection_subscale_tau(double speed, double h, double nu, double sigma_over_rho) {
  const double a = 2.0 * speed / h, b = 4.0 * nu / (h * h);
  const double s = a * a + b * b + sigma_over_rho * sigma_over_rho;
  return s > 0.0 ? 1.0 / std::sqrt(s) : 0.0;
}

void convective_derivative_projection(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                                      std::span<const double> grad, std::span<const double> w,
                                      std::span<double> out) {
  convective_derivative_projection(tet_nodes, volume, grad, w, out, 0, volume.size());
}

void convective_derivative_projection(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                                      std::span<const double> grad, std::span<const double> w,
                                      std::span<double> out, size_t begin, size_t end) {
  for (size_t t = begin; t < end; ++t) {
    const double v = volume[t];
    if (v <= 0.0) continue;
    const int32_t* nodes = &tet_nodes[4 * t];
    const double* g = &grad[12 * t];
    double wbar[3] = {0.0, 0.0, 0.0}, gw[3][3] = {};  // gw[d][j] = d w_d / d x_j
    for (int n = 0; n < 4; ++n) {
      const double* wn = &w[3 * static_cast<size_t>(nodes[n])];
      for (int d = 0; d < 3; ++d) {
        wbar[d] += 0.25 * wn[d];
        for (int j = 0; j < 3; ++j) gw[d][j] += wn[d] * g[3 * n + j];
      }
    }
    double c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = 0.25 * v * (wbar[0] * gw[d][0] + wbar[1] * gw[d][1] + wbar[2] * gw[d][2]);
    for (int n = 0; n < 4; ++n)
      for (int d = 0; d < 3; ++d) out[3 * static_cast<size_t>(nodes[n]) + d] += c[d];
  }
}

}  // namespace rift::kernels
