#include "kernels/stable_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rift::kernels {

namespace {

// Smallest altitude h = 3V / A_max = |det E| / max |face cross product| (both sides carry the same factor 2).
// Returns 0 for tets with det E <= 0.
double smallest_altitude(const double* p[4]) {
  double e[3][3];  // e[c] = p[c+1] - p[0]
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) e[c][i] = p[c + 1][i] - p[0][i];
  auto cross_norm = [](const double* a, const double* b, const double* c) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  };
  const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  if (!(det > 0.0)) return 0.0;
  const double a_max = std::max({cross_norm(p[1], p[2], p[3]), cross_norm(p[0], p[2], p[3]),
                                 cross_norm(p[0], p[1], p[3]), cross_norm(p[0], p[1], p[2])});
  return det / a_max;
}

// Calls visit(dt_elastic, material) for every tet of positive volume in [begin, end).
template <class Visit>
void for_each_tet_step(std::span<const double> x, std::span<const int32_t> tet_nodes,
                       std::span<const int32_t> material, std::span<const TetMaterial> materials,
                       std::span<const double> density, size_t begin, size_t end, Visit visit) {
  for (size_t t = begin; t < end; ++t) {
    const double* p[4];
    for (int a = 0; a < 4; ++a) p[a] = &x[3 * static_cast<size_t>(tet_nodes[4 * t + a])];
    const double h = smallest_altitude(p);
    if (!(h > 0.0)) continue;
    const size_t m = static_cast<size_t>(material[t]);
    const double c_p = std::sqrt((materials[m].lambda + 2.0 * materials[m].mu) / density[m]);
    visit(h / c_p, materials[m]);
  }
}

}  // namespace

double tet_stable_step(std::span<const double> x, std::span<const int32_t> tet_nodes,
                       std::span<const int32_t> material, std::span<const TetMaterial> materials,
                       std::span<const double> density, size_t begin, size_t end) {
  double dt = std::numeric_limits<double>::infinity();
  for_each_tet_step(x, tet_nodes, material, materials, density, begin, end,
                    [&](double dt_e, const TetMaterial&) { dt = std::min(dt, dt_e); });
  return dt;
}

double viscous_stable_step(double dt_elastic, double eta, double p_modulus) {
  const double a = eta / p_modulus;
  return dt_elastic * dt_elastic / (std::sqrt(dt_elastic * dt_elastic + a * a) + a);
}

double tet_damped_stable_step(std::span<const double> x, std::span<const int32_t> tet_nodes,
                              std::span<const int32_t> material, std::span<const TetMaterial> materials,
                              std::span<const double> density, size_t begin, size_t end) {
  double dt = std::numeric_limits<double>::infinity();
  for_each_tet_step(x, tet_nodes, material, materials, density, begin, end,
                    [&](double dt_e, const TetMaterial& m) {
                      dt = std::min(dt, viscous_stable_step(dt_e, m.eta, m.lambda + 2.0 * m.mu));
                    });
  return dt;
}

}  // namespace rift::kernels
