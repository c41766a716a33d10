#include "kernels/node_integration.hpp"

#include <cmath>

namespace rift::kernels {

size_t integrate_nodes(const NodeIntegrationArgs& a, const ForceSlots& s, size_t begin, size_t end) {
  size_t bad = 0;
  for (size_t n = begin; n < end; ++n) {
    double f[3] = {0.0, 0.0, 0.0};
    for (int32_t k = s.node_range[2 * n]; k < s.node_range[2 * n + 1]; ++k) {
      const int64_t slot = s.slots[k];
      const double* src =
          slot < s.split_slot ? &s.primary[3 * slot] : &s.secondary[3 * (slot - s.split_slot)];
      f[0] += src[0];
      f[1] += src[1];
      f[2] += src[2];
    }
    const double w = a.inv_mass[n];
    const int32_t bc = a.held_velocity[n];
    bool finite = true;
    for (int c = 0; c < 3; ++c) {
      const size_t i = 3 * n + c;
      a.f[i] = f[c];
      const double held = bc >= 0 ? a.prescribed[3 * bc + c] : 0.0;
      const double v = a.free_mask[i] ? a.v[i] + a.dt * (f[c] * w + a.gravity[c]) : held;
      a.v[i] = v;
      a.x[i] += a.dt * v;
      finite = finite && std::isfinite(a.x[i]) && std::isfinite(v);
    }
    bad += finite ? 0 : 1;
  }
  return bad;
}

}  // namespace rift::kernels
