#include "kernels/softening.hpp"

namespace rift::kernels {

namespace {

double integrate_z() {
  // 5-point Gauss-Legendre on [-1, 1]: nodes 0, +-(1/3) sqrt(5 -+ 2 sqrt(10/7)),
  // weights 128/225, (322 +- 13 sqrt(70)) / 900.
  const double r = 2.0 * std::sqrt(10.0 / 7.0);
  const double node[5] = {0.0, std::sqrt(5.0 - r) / 3.0, -std::sqrt(5.0 - r) / 3.0, std::sqrt(5.0 + r) / 3.0,
                          -std::sqrt(5.0 + r) / 3.0};
  const double s70 = 13.0 * std::sqrt(70.0);
  const double weight[5] = {128.0 / 225.0, (322.0 + s70) / 900.0, (322.0 + s70) / 900.0,
                            (322.0 - s70) / 900.0, (322.0 - s70) / 900.0};
  constexpr int panels = 64;
  const double half = 0.5 / panels;
  double sum = 0.0;
  for (int k = 0; k < panels; ++k) {
    const double mid = (k + 0.5) / panels;
    for (int q = 0; q < 5; ++q) sum += weight[q] * softening_z(mid + half * node[q]);
  }
  return sum * half;
}

}  // namespace

double softening_integral() {
  static const double Z = integrate_z();
  return Z;
}

}  // namespace rift::kernels
