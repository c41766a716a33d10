#include "kernels/fluid_element.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/tet_geometry.hpp"

namespace rift::kernels {

double p1_gradients(const double* x, double* g) {
  const double* const corner[4] = {x, x + 3, x + 6, x + 9};
  double e[3][3], rows[3][3];
  tet_edges(corner, e);
  // Rows of J^-1 (J has the edges e_s as columns) are the gradients of N_1..N_3 (kernels/tet_geometry.hpp).
  const double det = tet_inverse_rows(e, rows);
  if (!(det > 0.0)) {
    std::fill(g, g + 12, 0.0);
    return std::isfinite(det) ? det / 6.0 : 0.0;
  }
  const double inv = 1.0 / det;
  for (int d = 0; d < 3; ++d) {
    g[3 + d] = rows[0][d] * inv;
    g[6 + d] = rows[1][d] * inv;
    g[9 + d] = rows[2][d] * inv;
    g[d] = -(g[3 + d] + g[6 + d] + g[9 + d]);
  }
  return det / 6.0;
}

double tet_max_edge(const double* x) {
  double h2 = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      double s = 0.0;
      for (int d = 0; d < 3; ++d) s += (x[3 * a + d] - x[3 * b + d]) * (x[3 * a + d] - x[3 * b + d]);
      h2 = std::max(h2, s);
    }
  return std::sqrt(h2);
}

void p1_mass(double volume, double* m) {
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) m[4 * a + b] = volume * (a == b ? 2.0 : 1.0) / 20.0;
}

void p1_stiffness(double volume, const double* g, double* k) {
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      k[4 * a + b] =
          volume * (g[3 * a] * g[3 * b] + g[3 * a + 1] * g[3 * b + 1] + g[3 * a + 2] * g[3 * b + 2]);
}

void p1_convection(double volume, const double* g, const double* w, double* c) {
  double sum[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n < 4; ++n)
    for (int d = 0; d < 3; ++d) sum[d] += w[3 * n + d];
  for (int a = 0; a < 4; ++a) {
    const double wa[3] = {sum[0] + w[3 * a], sum[1] + w[3 * a + 1], sum[2] + w[3 * a + 2]};
    for (int b = 0; b < 4; ++b)
      c[4 * a + b] = volume / 20.0 * (wa[0] * g[3 * b] + wa[1] * g[3 * b + 1] + wa[2] * g[3 * b + 2]);
  }
}

void p1_streamline_diffusion(double volume, const double* g, const double* wbar, double tau, double* s) {
  double wg[4];
  for (int a = 0; a < 4; ++a) wg[a] = wbar[0] * g[3 * a] + wbar[1] * g[3 * a + 1] + wbar[2] * g[3 * a + 2];
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) s[4 * a + b] = tau * volume * wg[a] * wg[b];
}

size_t p1_prepare(std::span<const double> x, std::span<const int32_t> tet_nodes, std::span<double> volume,
                  std::span<double> grad, std::span<double> h) {
  const size_t n_tets = tet_nodes.size() / 4;
  size_t bad = 0;
  for (size_t t = 0; t < n_tets; ++t) {
    double xt[12];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) xt[3 * a + d] = x[3 * static_cast<size_t>(tet_nodes[4 * t + a]) + d];
    const double v = p1_gradients(xt, &grad[12 * t]);
    if (!(v > 0.0)) ++bad;
    volume[t] = v > 0.0 ? v : 0.0;
    h[t] = tet_max_edge(xt);
  }
  return bad;
}

namespace {

// One tet's momentum contributions: km[4 i + j] the matrix entry (node_i, node_j), kr[3 i + d] the
// right-hand side of row node_i, component d. False (nothing written) for a tet with V <= 0.
inline bool momentum_element(const FluidMomentumArgs& a, size_t t, double* km, double* kr) {
  const int32_t* nodes = &a.tet_nodes[4 * t];
  const double v = a.volume[t];
  if (v <= 0.0) return false;
  const double rdt = a.rho / a.dt;
  const double* g = &a.grad[12 * t];
  double w[12], wbar[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n < 4; ++n)
    for (int d = 0; d < 3; ++d) {
      w[3 * n + d] = a.advect[3 * static_cast<size_t>(nodes[n]) + d];
      wbar[d] += 0.25 * w[3 * n + d];
    }
  double m[16], k[16], c[16], s[16];
  p1_mass(v, m);
  p1_stiffness(v, g, k);
  p1_convection(v, g, w, c);
  const double tau_s = a.supg_tau.empty() ? 0.0 : a.supg_tau[t];
  if (tau_s > 0.0)
    p1_streamline_diffusion(v, g, wbar, a.rho * tau_s, s);
  else
    std::fill(s, s + 16, 0.0);
  const double sigma = a.sigma.empty() ? 0.0 : a.sigma[t];
  // Pressure: constant cell gradient; -int N_a grad p = -(V/4) grad p.
  double gp[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n < 4; ++n) {
    const double pn = a.pressure[nodes[n]];
    for (int d = 0; d < 3; ++d) gp[d] += g[3 * n + d] * pn;
  }
  double cell_force[3] = {0.0, 0.0, 0.0};
  for (int d = 0; d < 3; ++d) {
    cell_force[d] = -gp[d];
    if (!a.source.empty()) cell_force[d] += a.source[3 * t + d];
    if (sigma != 0.0 && !a.target.empty()) cell_force[d] += sigma * a.target[3 * t + d];
  }
  // Node values gathered once: each is used by the 4 rows.
  double uo[12], bf[12];
  const bool with_body_force = !a.body_force.empty();
  for (int n = 0; n < 4; ++n)
    for (int d = 0; d < 3; ++d) {
      const size_t i = 3 * static_cast<size_t>(nodes[n]) + d;
      uo[3 * n + d] = a.u_old[i];
      bf[3 * n + d] = with_body_force ? a.body_force[i] : 0.0;
    }
  for (int i = 0; i < 4; ++i) {
    double r[3] = {0.0, 0.0, 0.0};
    for (int j = 0; j < 4; ++j) {
      const double l = a.mu * k[4 * i + j] + a.rho * c[4 * i + j] + s[4 * i + j];
      double kij = rdt * m[4 * i + j] + a.theta * l;
      if (i == j) kij += sigma * 0.25 * v;
      km[4 * i + j] = kij;
      const double rij = rdt * m[4 * i + j] - (1.0 - a.theta) * l;
      for (int d = 0; d < 3; ++d) {
        r[d] += rij * uo[3 * j + d];
        if (with_body_force) r[d] += m[4 * i + j] * bf[3 * j + d];
      }
    }
    for (int d = 0; d < 3; ++d) kr[3 * i + d] = r[d] + 0.25 * v * cell_force[d];
  }
  if (tau_s > 0.0 && !a.convection_projection.empty()) {
    double eta[3] = {0.0, 0.0, 0.0};
    for (int n = 0; n < 4; ++n)
      for (int d = 0; d < 3; ++d)
        eta[d] += 0.25 * a.convection_projection[3 * static_cast<size_t>(nodes[n]) + d];
    for (int i = 0; i < 4; ++i) {
      const double f =
          a.rho * tau_s * v * (wbar[0] * g[3 * i] + wbar[1] * g[3 * i + 1] + wbar[2] * g[3 * i + 2]);
      for (int d = 0; d < 3; ++d) kr[3 * i + d] += f * eta[d];
    }
  }
  return true;
}

}  // namespace

void fluid_assemble_momentum(const FluidMomentumArgs& a) {
  fluid_assemble_momentum(a, 0, a.tet_nodes.size() / 4);
}

void fluid_assemble_momentum(const FluidMomentumArgs& a, size_t begin, size_t end) {
  for (size_t t = begin; t < end; ++t) {
    double km[16], kr[12];
    if (!momentum_element(a, t, km, kr)) continue;
    for (int e = 0; e < 16; ++e) a.matrix_values[a.slot[16 * t + e]] += km[e];
    for (int i = 0; i < 4; ++i) {
      const size_t ni = static_cast<size_t>(a.tet_nodes[4 * t + i]);
      for (int d = 0; d < 3; ++d) a.rhs[3 * ni + d] += kr[3 * i + d];
    }
  }
}

namespace {

// body(t, i, j, k_ij) for every free row i of every tet t in [begin, end) with V > 0, j over all 4 corners.
template <class Body>
void for_each_free_row_entry(const ScalarLaplacianArgs& a, size_t begin, size_t end, const Body& body) {
  for (size_t t = begin; t < end; ++t) {
    const int32_t* nodes = &a.tet_nodes[4 * t];
    const double v = a.volume[t];
    if (v <= 0.0) continue;
    double k[16];
    p1_stiffness(v * a.coef[t], &a.grad[12 * t], k);
    for (int i = 0; i < 4; ++i) {
      if (a.fixed[nodes[i]]) continue;
      for (int j = 0; j < 4; ++j) body(t, i, j, k[4 * i + j]);
    }
  }
}

}  // namespace

void scalar_laplacian_assemble(const ScalarLaplacianArgs& a) {
  scalar_laplacian_matrix(a, 0, a.tet_nodes.size() / 4);
  scalar_laplacian_fix_rows(a);
  if (!a.rhs.empty()) scalar_laplacian_dirichlet_rhs(a);
}

// Each free row loses k_ij value_j for its fixed columns j; fixed rows hold their value.
void scalar_laplacian_dirichlet_rhs(const ScalarLaplacianArgs& a) {
  for_each_free_row_entry(a, 0, a.tet_nodes.size() / 4, [&](size_t t, int i, int j, double k) {
    const int32_t nj = a.tet_nodes[4 * t + j];
    if (a.fixed[nj]) a.rhs[a.tet_nodes[4 * t + i]] -= k * a.value[nj];
  });
  for (size_t n = 0; n < a.fixed.size(); ++n)
    if (a.fixed[n]) a.rhs[n] = a.value[n];
}

void scalar_laplacian_matrix(const ScalarLaplacianArgs& a, size_t begin, size_t end) {
  for_each_free_row_entry(a, begin, end, [&](size_t t, int i, int j, double k) {
    if (!a.fixed[a.tet_nodes[4 * t + j]]) a.matrix_values[a.slot[16 * t + 4 * i + j]] += k;
  });
}

void scalar_laplacian_fix_rows(const ScalarLaplacianArgs& a) {
  for (size_t n = 0; n < a.fixed.size(); ++n)
    if (a.fixed[n]) a.matrix_values[a.diag_slot[n]] = 1.0;
}

namespace {

// One tet's terms of fluid_pressure_rhs: x[q] is what row node_q loses. False for V <= 0.
inline bool pressure_rhs_element(const FluidPressureRhsArgs& a, size_t t, double* x) {
  const int32_t* nodes = &a.tet_nodes[4 * t];
  const double v = a.volume[t];
  if (v <= 0.0) return false;
  const double* g = &a.grad[12 * t];
  double div = 0.0, r[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n < 4; ++n) {
    const size_t nn = static_cast<size_t>(nodes[n]);
    for (int d = 0; d < 3; ++d) {
      div += g[3 * n + d] * a.u[3 * nn + d];
      r[d] += g[3 * n + d] * a.p[nn] - (a.xi.empty() ? 0.0 : 0.25 * a.xi[3 * nn + d]);
    }
  }
  const double tau = a.tau_p.empty() ? 0.0 : a.tau_p[t];
  const double w = a.div_weight.empty() ? 1.0 : a.div_weight[t];
  for (int q = 0; q < 4; ++q)
    x[q] = 0.25 * v * w * div + tau * v * (g[3 * q] * r[0] + g[3 * q + 1] * r[1] + g[3 * q + 2] * r[2]);
  const double h = a.relative_flux.empty() ? 0.0 : a.relative_flux[t];
  if (h == 0.0) return true;  // a cell the fluid fills: no relative flux to add
  double flux[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n < 4; ++n) {
    const size_t nn = static_cast<size_t>(nodes[n]);
    for (int d = 0; d < 3; ++d)
      flux[d] += g[3 * n + d] * a.p[nn] - (a.body_force.empty() ? 0.0 : 0.25 * a.body_force[3 * nn + d]);
  }
  for (int q = 0; q < 4; ++q)
    x[q] += h * v * (g[3 * q] * flux[0] + g[3 * q + 1] * flux[1] + g[3 * q + 2] * flux[2]);
  return true;
}

// One tet's term of p1_weighted_gradient (the same for its 4 nodes): (V/4) w_t grad p_t.
inline void weighted_gradient_element(const WeightedGradientArgs& a, size_t t, double* f_gp) {
  const int32_t* nodes = &a.tet_nodes[4 * t];
  double gp[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n < 4; ++n)
    for (int d = 0; d < 3; ++d) gp[d] += a.grad[12 * t + 3 * n + d] * a.p[nodes[n]];
  const double f = 0.25 * a.volume[t] * (a.w.empty() ? 1.0 : a.w[t]);
  for (int d = 0; d < 3; ++d) f_gp[d] = f * gp[d];
}

}  // namespace

void fluid_pressure_rhs(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                        std::span<const double> grad, std::span<const double> u, std::span<const double> p,
                        std::span<const double> xi, std::span<const double> tau_p, std::span<double> rhs) {
  fluid_pressure_rhs({tet_nodes, volume, grad, u, p, xi, tau_p}, rhs, 0, tet_nodes.size() / 4);
}

void fluid_pressure_rhs(const FluidPressureRhsArgs& a, std::span<double> rhs, size_t begin, size_t end) {
  for (size_t t = begin; t < end; ++t) {
    double x[4];
    if (!pressure_rhs_element(a, t, x)) continue;
    for (int q = 0; q < 4; ++q) rhs[a.tet_nodes[4 * t + q]] -= x[q];
  }
}

void p1_divergence(std::span<const int32_t> tet_nodes, std::span<const double> grad,
                   std::span<const double> u, std::span<double> div) {
  const size_t n_tets = tet_nodes.size() / 4;
  for (size_t t = 0; t < n_tets; ++t) {
    double s = 0.0;
    for (int n = 0; n < 4; ++n) {
      const size_t nn = static_cast<size_t>(tet_nodes[4 * t + n]);
      for (int d = 0; d < 3; ++d) s += grad[12 * t + 3 * n + d] * u[3 * nn + d];
    }
    div[t] = s;
  }
}

void p1_weighted_gradient(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                          std::span<const double> grad, std::span<const double> p, std::span<const double> w,
                          std::span<double> out) {
  p1_weighted_gradient({tet_nodes, volume, grad, p, w}, out, 0, tet_nodes.size() / 4);
}

void p1_weighted_gradient(const WeightedGradientArgs& a, std::span<double> out, size_t begin, size_t end) {
  for (size_t t = begin; t < end; ++t) {
    double f_gp[3];
    weighted_gradient_element(a, t, f_gp);
    for (int n = 0; n < 4; ++n)
      for (int d = 0; d < 3; ++d) out[3 * static_cast<size_t>(a.tet_nodes[4 * t + n]) + d] += f_gp[d];
  }
}

}  // namespace rift::kernels
