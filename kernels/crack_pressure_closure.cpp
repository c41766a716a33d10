#include "kernels/crack_pressure_closure.hpp"

namespace rift::kernels {

void add_pressure_area_vectors(std::span<const int32_t> corner_nodes, std::span<const double> normal,
                               std::span<const double> area, std::span<double> area_vector) {
  for (size_t t = 0; t < area.size(); ++t)
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) {
        const double a = area[t] / 3.0 * normal[3 * t + size_t(d)];
        area_vector[3 * size_t(corner_nodes[6 * t + size_t(k)]) + size_t(d)] += a;
        area_vector[3 * size_t(corner_nodes[6 * t + 3 + size_t(k)]) + size_t(d)] -= a;
      }
}

void add_closure_compliance(const CrackClosureNodes& nodes, double dt, double damping_factor,
                            std::span<double> compliance) {
  const double s = dt * dt * damping_factor;
  for (size_t n = 0; n < nodes.vertex.size(); ++n) {
    if (nodes.vertex[n] < 0) continue;
    double a2 = 0.0;
    for (size_t d = 0; d < 3; ++d)
      if (nodes.free_mask[3 * n + d]) a2 += nodes.area_vector[3 * n + d] * nodes.area_vector[3 * n + d];
    compliance[size_t(nodes.vertex[n])] += s * a2 * nodes.inv_mass[n];
  }
}

void apply_closure(const CrackClosureNodes& nodes, double dt, double damping_factor,
                   std::span<const double> pressure_change, std::span<double> x, std::span<double> v) {
  for (size_t n = 0; n < nodes.vertex.size(); ++n) {
    if (nodes.vertex[n] < 0) continue;
    const double dv = dt * damping_factor * pressure_change[size_t(nodes.vertex[n])] * nodes.inv_mass[n];
    for (size_t d = 0; d < 3; ++d)
      if (nodes.free_mask[3 * n + d]) {
        v[3 * n + d] += dv * nodes.area_vector[3 * n + d];
        x[3 * n + d] += dt * dv * nodes.area_vector[3 * n + d];
      }
  }
}

}  // namespace rift::kernels
