#include "kernels/stable_step.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/tet_geometry.hpp"

namespace rift::kernels {

namespace {

// Smallest altitude h = 3V / A_max = |det E| / max |face cross product| (both sides carry the same factor 2).
// Returns 0 for tets with det E <= 0.
double smallest_altitude(const double* p[4]) {
  double e[3][3];
  tet_edges(p, e);
  auto cross_norm = [](const double* a, const double* b, const double* c) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  };
  const double det = tet_six_volume(e);
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

double tet_highest_omega2(const double c[4][3], const TetMaterial& m, double density) {
  double e[3][3], rows[3][3];
  tet_edges(c, e);
  const double det = tet_inverse_rows(e, rows);  // rows / det: the gradients of N_1, N_2, N_3
  if (!(det > 0.0)) return 0.0;
  Eigen::Vector3d g[4];
  for (int a = 1; a < 4; ++a) g[a] = Eigen::Vector3d(rows[a - 1][0], rows[a - 1][1], rows[a - 1][2]) / det;
  g[0] = -(g[1] + g[2] + g[3]);
  // M^-1 K_e with m = rho V / 4 on every corner and K_e = V B^T D B: V cancels.
  Eigen::Matrix<double, 12, 12> A;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      A.block<3, 3>(3 * a, 3 * b) = 4.0 / density *
                                    (m.lambda * g[a] * g[b].transpose() + m.mu * g[b] * g[a].transpose() +
                                     m.mu * g[a].dot(g[b]) * Eigen::Matrix3d::Identity());
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>>(A, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

double tet_exact_stable_step(std::span<const double> x, std::span<const int32_t> tet_nodes,
                             std::span<const int32_t> material, std::span<const TetMaterial> materials,
                             std::span<const double> density, size_t begin, size_t end) {
  double dt = std::numeric_limits<double>::infinity();
  for (size_t t = begin; t < end; ++t) {
    double c[4][3];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) c[a][i] = x[3 * static_cast<size_t>(tet_nodes[4 * t + a]) + i];
    const size_t mat = static_cast<size_t>(material[t]);
    const TetMaterial& m = materials[mat];
    const double omega2 = tet_highest_omega2(c, m, density[mat]);
    if (omega2 > 0.0)
      dt = std::min(dt, viscous_stable_step(2.0 / std::sqrt(omega2), m.eta, m.lambda + 2.0 * m.mu));
  }
  return dt;
}

void add_tet_node_stiffness(std::span<const int32_t> tet_nodes, std::span<const double> tet_step,
                            std::span<const double> tet_mass, std::span<double> stiffness) {
  for (size_t t = 0; t < tet_step.size(); ++t) {
    if (!std::isfinite(tet_step[t])) continue;                   // degenerate: no step, no stiffness
    const double k = tet_mass[t] / (tet_step[t] * tet_step[t]);  // (2 / dt)^2 x (rho V / 4)
    for (int a = 0; a < 4; ++a) stiffness[static_cast<size_t>(tet_nodes[4 * t + a])] += k;
  }
}

MassScaling scale_masses_to_step(std::span<const double> stiffness, double step, std::span<double> mass,
                                 std::span<double> inv_mass) {
  MassScaling r;
  for (size_t n = 0; n < mass.size(); ++n) {
    const double needed = 0.25 * stiffness[n] * step * step;
    if (!(mass[n] > 0.0) || needed <= mass[n]) continue;  // massless nodes only follow their BCs
    const double factor = needed / mass[n];
    if (factor > r.largest_factor) r.largest_factor = factor, r.largest_node = static_cast<int64_t>(n);
    r.added += needed - mass[n];
    ++r.scaled_nodes;
    mass[n] = needed;
    inv_mass[n] = 1.0 / needed;
  }
  return r;
}

double node_stable_step(std::span<const double> stiffness, std::span<const double> mass) {
  double dt = std::numeric_limits<double>::infinity();
  for (size_t n = 0; n < mass.size(); ++n)
    if (stiffness[n] > 0.0 && mass[n] > 0.0) dt = std::min(dt, 2.0 * std::sqrt(mass[n] / stiffness[n]));
  return dt;
}

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
