#include "kernels/fracture_flow.hpp"

#include <cmath>

namespace rift::kernels {

double pressure_of_mass(const FluidEos& eos, double m, double v0, double compliance, double p_ref) {
  // rho(p) V(p) = m with rho = a + b p, V = c0 + C p: b C p^2 + (a C + b c0) p + (a c0 - m) = 0.
  const double b = eos.density0 / eos.bulk_modulus;
  const double a = eos.density0 - b * eos.pressure0;
  const double c0 = v0 - compliance * p_ref;
  if (compliance <= 0.0) return (m / v0 - a) / b;
  const double qa = b * compliance, qb = a * compliance + b * c0, qc = a * c0 - m;
  const double disc = std::sqrt(std::max(qb * qb - 4.0 * qa * qc, 0.0));
  // The root where d(rho V)/dp = 2 qa p + qb > 0; written without cancellation.
  return qb >= 0.0 ? (-2.0 * qc) / (qb + disc) : (-qb + disc) / (2.0 * qa);
}

double p1_edge_coefficients(const double* x0, const double* x1, const double* x2, double k[3]) {
  double e[3][3];
  for (int d = 0; d < 3; ++d) {
    e[0][d] = x2[d] - x1[d];
    e[1][d] = x0[d] - x2[d];
    e[2][d] = x1[d] - x0[d];
  }
  const double n[3] = {e[2][1] * (-e[1][2]) - e[2][2] * (-e[1][1]),
                       e[2][2] * (-e[1][0]) - e[2][0] * (-e[1][2]),
                       e[2][0] * (-e[1][1]) - e[2][1] * (-e[1][0])};
  const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const double s = 1.0 / (4.0 * area);
  k[0] = dot(e[1], e[2]) * s;  // K_12
  k[1] = dot(e[2], e[0]) * s;  // K_20
  k[2] = dot(e[0], e[1]) * s;  // K_01
  return area;
}

CrackTriangle crack_triangle(const double* corner[6]) {
  CrackTriangle t;
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d) t.mid[k][d] = 0.5 * (corner[k][d] + corner[k + 3][d]);
  double a[3], b[3];
  for (int d = 0; d < 3; ++d) {
    a[d] = t.mid[1][d] - t.mid[0][d];
    b[d] = t.mid[2][d] - t.mid[0][d];
  }
  // Corners 0-2 are the first tet's face in reversed outward order, so (m1 - m0) x (m2 - m0) points into
  // the first tet: from the second face into the first.
  const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  t.area = 0.5 * len;
  for (int d = 0; d < 3; ++d) t.normal[d] = len > 0.0 ? n[d] / len : 0.0;
  for (int k = 0; k < 3; ++k) {
    double o = 0.0;
    for (int d = 0; d < 3; ++d) o += (corner[k][d] - corner[k + 3][d]) * t.normal[d];
    t.opening[k] = o;
  }
  return t;
}

}  // namespace rift::kernels
