#include "kernels/joint_initial_state.hpp"

#include <cmath>

namespace rift::kernels {

namespace {

// 1 - sqrt(1 - r) for r in [0, 1), as r / (1 + sqrt(1 - r)): no cancellation at small r.
double rising_root(double r) {
  return r / (1.0 + std::sqrt(1.0 - r));
}

}  // namespace

bool joint_initial_offset(const JointMaterial& m, double h, const double n[3], const double traction[3],
                          Softening softening, double Z, double offset[3]) {
  (void)softening;
  (void)Z;
  for (int c = 0; c < 3; ++c) offset[c] = 0.0;
  const double sigma_n = traction[0] * n[0] + traction[1] * n[1] + traction[2] * n[2];
  double shear[3];
  for (int c = 0; c < 3; ++c) shear[c] = traction[c] - sigma_n * n[c];
  const double tau = std::sqrt(shear[0] * shear[0] + shear[1] * shear[1] + shear[2] * shear[2]);
  const double k = m.penalty / h;
  const double fs = sigma_n < 0.0 ? m.cohesion - sigma_n * m.tan_friction : m.cohesion;
  if (!(sigma_n < m.tensile_strength) || !(tau < fs)) return false;  // NaN tractions fail too
  const double o_n =
      sigma_n <= 0.0 ? sigma_n / k : 2.0 * m.tensile_strength / k * rising_root(sigma_n / m.tensile_strength);
  const double o_s = 2.0 * fs / k * rising_root(tau / fs);
  const double along = tau > 0.0 ? o_s / tau : 0.0;
  for (int c = 0; c < 3; ++c) offset[c] = o_n * n[c] + along * shear[c];
  return true;
}

}  // namespace rift::kernels
