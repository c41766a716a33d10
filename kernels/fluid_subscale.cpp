#include "kernels/fluid_subscale.hpp"

namespace rift::kernels {

void pressure_subscale_rhs(const PressureSubscaleArgs& a, std::span<const double> subscale,
                           std::span<double> rhs) {
  const size_t nt = a.volume.size();
  for (size_t t = 0; t < nt; ++t) {
    const double* s = &subscale[3 * t];
    if (s[0] == 0.0 && s[1] == 0.0 && s[2] == 0.0) continue;
    const double k = a.tau_t[t] * a.rho_over_dt * a.volume[t];
    const double* g = &a.grad[12 * t];
    for (int q = 0; q < 4; ++q)
      rhs[static_cast<size_t>(a.tet_nodes[4 * t + q])] +=
          k * (g[3 * q] * s[0] + g[3 * q + 1] * s[1] + g[3 * q + 2] * s[2]);
  }
}

void pressure_subscale_update(const PressureSubscaleArgs& a, std::span<const double> p,
                              std::span<const double> xi, std::span<double> subscale) {
  const size_t nt = a.volume.size();
  for (size_t t = 0; t < nt; ++t) {
    const double* g = &a.grad[12 * t];
    double residual[3] = {0.0, 0.0, 0.0};  // grad p_t - xibar_t
    for (int q = 0; q < 4; ++q) {
      const size_t n = static_cast<size_t>(a.tet_nodes[4 * t + q]);
      for (int d = 0; d < 3; ++d) residual[d] += g[3 * q + d] * p[n] - 0.25 * xi[3 * n + d];
    }
    double* s = &subscale[3 * t];
    for (int d = 0; d < 3; ++d) s[d] = a.tau_t[t] * (a.rho_over_dt * s[d] - residual[d]);
  }
}

}  // namespace rift::kernels
