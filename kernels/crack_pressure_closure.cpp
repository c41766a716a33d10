#include "kernels/crack_pressure_closure.hpp"

namespace rift::kernels {

void gather_area_vectors(std::span<const int32_t> corner_start, std::span<const int32_t> corners,
                         std::span<const double> normal, std::span<const double> area,
                         std::span<const double> opening, double floor, std::span<double> area_vector,
                         std::span<double> open_area_vector, size_t begin, size_t end) {
  for (size_t e = begin; e < end; ++e) {
    double all[3] = {0.0, 0.0, 0.0}, open[3] = {0.0, 0.0, 0.0};
    for (int32_t k = corner_start[e]; k < corner_start[e + 1]; ++k) {
      const size_t t = size_t(corners[size_t(k)]) / 6, c = size_t(corners[size_t(k)]) % 6;
      const bool side_a = c < 3;
      const bool is_open = opening[3 * t + c % 3] > floor;
      for (size_t d = 0; d < 3; ++d) {
        const double a = area[t] / 3.0 * normal[3 * t + d];
        all[d] = side_a ? all[d] + a : all[d] - a;
        if (is_open) open[d] = side_a ? open[d] + a : open[d] - a;
      }
    }
    for (size_t d = 0; d < 3; ++d) {
      area_vector[3 * e + d] = all[d];
      open_area_vector[3 * e + d] = open[d];
    }
  }
}

void add_wall_area_vectors(std::span<const int32_t> face_nodes, std::span<const int32_t> face_entries,
                           std::span<const double> x, std::span<double> area_vector) {
  for (size_t f = 0; f < face_nodes.size() / 3; ++f) {
    const double* p[3];
    for (size_t k = 0; k < 3; ++k) p[k] = &x[3 * size_t(face_nodes[3 * f + k])];
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    for (size_t k = 0; k < 3; ++k)
      for (size_t d = 0; d < 3; ++d) area_vector[3 * size_t(face_entries[3 * f + k]) + d] -= n[d] / 6.0;
  }
}

double closure_weight(const CrackClosureNodes& nodes, size_t i) {
  const std::span<const double> open =
      nodes.open_area_vector.empty() ? nodes.area_vector : nodes.open_area_vector;
  double w = 0.0;
  for (size_t d = 0; d < 3; ++d)
    if (nodes.free_mask[3 * i + d]) w += open[3 * i + d] * nodes.area_vector[3 * i + d];
  return w * nodes.inv_mass[i];
}

void add_closure_compliance(const CrackClosureNodes& nodes, double dt, double damping_factor,
                            std::span<double> compliance) {
  const double s = dt * dt * damping_factor;
  for (size_t i = 0; i < nodes.node.size(); ++i)
    compliance[size_t(nodes.vertex[i])] += s * closure_weight(nodes, i);
}

double apply_closure(const CrackClosureNodes& nodes, double dt, double damping_factor,
                     std::span<const double> felt, std::span<const double> now, std::span<double> x,
                     std::span<double> v) {
  return apply_closure_block(nodes, dt, damping_factor, felt, now, x, v, 0, nodes.node.size());
}

double apply_closure_block(const CrackClosureNodes& nodes, double dt, double damping_factor,
                           std::span<const double> felt, std::span<const double> now, std::span<double> x,
                           std::span<double> v, size_t begin, size_t end) {
  // Far enough ahead to cover a miss to memory with the work of the entries in between.
  constexpr size_t kAhead = 16;
  double work = 0.0;
  for (size_t i = begin; i < end; ++i) {
    if (i + kAhead < end) {
      const size_t ahead = 3 * size_t(nodes.node[i + kAhead]);
      __builtin_prefetch(&x[ahead], 1);
      __builtin_prefetch(&x[ahead + 2], 1);  // a row may straddle two lines
      __builtin_prefetch(&v[ahead], 1);
      __builtin_prefetch(&v[ahead + 2], 1);
    }
    const size_t n = size_t(nodes.node[i]);
    const double dp = now[i] - felt[i];
    const double dv = dt * damping_factor * dp * nodes.inv_mass[i];
    for (size_t d = 0; d < 3; ++d)
      if (nodes.free_mask[3 * i + d]) {
        const double a = nodes.area_vector[3 * i + d], dvd = dv * a;
        work += dp * a * dt * (v[3 * n + d] + 0.5 * dvd) + felt[i] * a * dt * 0.5 * dvd;
        v[3 * n + d] += dvd;
        x[3 * n + d] += dt * dvd;
      }
  }
  return work;
}

}  // namespace rift::kernels
