#include "kernels/central_difference.hpp"

namespace rift::kernels {

void central_difference(const CentralDifferenceInput& in, std::span<double> x, std::span<double> v,
                        std::span<double> f, std::span<const double> inv_mass,
                        std::span<const uint8_t> free_mask, size_t begin, size_t end) {
  const double dt = in.dt;
  for (size_t n = begin; n < end; ++n) {
    const double w = inv_mass[n];
    for (int c = 0; c < 3; ++c) {
      const size_t i = 3 * n + c;
      // Held components keep their prescribed velocity; the mask is 0/1 so this stays branch-free.
      const double a = (f[i] * w + in.gravity[c]) * free_mask[i];
      v[i] += dt * a;
      x[i] += dt * v[i];
      f[i] = 0.0;
    }
  }
}

}  // namespace rift::kernels
