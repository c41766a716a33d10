#include "kernels/node_integration.hpp"

#include <bit>
#include <cmath>

namespace rift::kernels {

namespace {

// How many nodes ahead the gather's slots are prefetched. A node's joint slots point at rows written for
// later tets (a joint is numbered after its second tet), ahead of the streaming front where the hardware
// prefetcher does not look: without this the loads wait on memory one node at a time.
constexpr size_t kPrefetchAhead = 8;

// Inlined early on purpose: as a separate function GCC finds it free of side effects and drops the call.
[[gnu::always_inline]] inline void prefetch_slots(const ForceSlots& s, size_t n) {
  for (int32_t k = s.node_range[2 * n]; k < s.node_range[2 * n + 1]; ++k) {
    const int64_t slot = s.slots[k];
    const int src = (slot >= s.first_slot[1]) + (slot >= s.first_slot[2]);
    const int64_t row = (slot - s.first_slot[src]) >> (src == 1);  // source 1: pairs share a row
    const double* p = s.source[src].data() + 3 * row;
    __builtin_prefetch(p);
    __builtin_prefetch(p + 2);  // the record may straddle two lines
  }
}

// Damped is a template argument so the undamped pass keeps its instructions (and bits) exactly; WriteForce
// so the pass without a force output has no branch for it.
template <bool Damped, bool WriteForce>
NodeStepResult integrate(const NodeIntegrationArgs& a, const ForceSlots& s, size_t begin, size_t end) {
  NodeStepResult r;
  const double half_cdt = 0.5 * a.mass_damping * a.dt;
  const double keep = (1.0 - half_cdt) / (1.0 + half_cdt), gain = a.dt / (1.0 + half_cdt);
  for (size_t n = begin; n < end; ++n) {
    if (n + kPrefetchAhead < end) prefetch_slots(s, n + kPrefetchAhead);
    // Per source, so the work of each can be booked. A node's slots are grouped by source (tets, joints,
    // faces: set-up guarantees it), so three plain loops accumulate in registers without branching per slot.
    double f[3][3];
    int32_t k = s.node_range[2 * n];
    const int32_t k_end = s.node_range[2 * n + 1];
    for (int src = 0; src < 3; ++src) {
      double fx = 0.0, fy = 0.0, fz = 0.0;
      const double* base = s.source[src].data();
      if (src == 1) {  // pairs: row e >> 1, negated when e is odd
        for (; k < k_end && s.slots[k] < s.first_slot[2]; ++k) {
          const int64_t e = s.slots[k] - s.first_slot[1];
          const double* p = base + 3 * (e >> 1);
          const uint64_t sign = static_cast<uint64_t>(e & 1) << 63;  // negation flips the sign bit only
          fx += std::bit_cast<double>(std::bit_cast<uint64_t>(p[0]) ^ sign);
          fy += std::bit_cast<double>(std::bit_cast<uint64_t>(p[1]) ^ sign);
          fz += std::bit_cast<double>(std::bit_cast<uint64_t>(p[2]) ^ sign);
        }
      } else {
        for (; k < k_end && s.slots[k] < s.first_slot[src + 1]; ++k) {
          const double* p = base + 3 * (s.slots[k] - s.first_slot[src]);
          fx += p[0];
          fy += p[1];
          fz += p[2];
        }
      }
      f[src][0] = fx, f[src][1] = fy, f[src][2] = fz;
    }
    if (!a.external_node_force.empty())
      for (int c = 0; c < 3; ++c) f[2][c] += a.external_node_force[3 * n + c];
    if (!a.crack_node_force.empty())
      for (int c = 0; c < 3; ++c) f[2][c] += a.crack_node_force[3 * n + c];
    double fc[3] = {0.0, 0.0, 0.0};
    if (!a.node_force.empty())
      for (int c = 0; c < 3; ++c) fc[c] = a.node_force[3 * n + c];
    const double w = a.inv_mass[n], m = a.mass[n];
    bool finite = true;
    for (int c = 0; c < 3; ++c) {
      const size_t i = 3 * n + c;
      const double internal = f[0][c] + f[1][c] + fc[c];
      const double total = internal + f[2][c];
      if constexpr (WriteForce) a.f[i] = total;
      const double v_old = a.v[i];
      const int32_t bc = a.held_velocity[i];
      const double held = bc >= 0 ? a.prescribed[3 * bc + c] : 0.0;
      const bool is_free = a.free_mask[i];
      double v;
      if constexpr (Damped)
        v = is_free && w > 0.0 ? keep * v_old + gain * (total * w + a.gravity[c])
            : is_free          ? v_old + a.dt * (total * w + a.gravity[c])
                               : held;
      else
        v = is_free ? v_old + a.dt * (total * w + a.gravity[c]) : held;
      a.v[i] = v;
      a.x[i] += a.dt * v;
      finite = finite && std::isfinite(a.x[i]) && std::isfinite(v);
      const double dx = 0.5 * a.dt * (v_old + v);
      if constexpr (Damped)
        if (is_free && w > 0.0) r.damping += a.mass_damping * m * 0.5 * (v_old + v) * dx;
      r.work[0] += f[0][c] * dx;
      r.work[1] += f[1][c] * dx;
      r.work[3] += fc[c] * dx;
      // External: loads and gravity on a free component; on a held one, whatever the prescribed motion
      // needed beyond the internal forces (load + gravity + reaction = m dv/dt - internal).
      r.work[2] +=
          is_free ? (f[2][c] + m * a.gravity[c]) * dx : 0.5 * m * (v * v - v_old * v_old) - internal * dx;
    }
    r.non_finite += finite ? 0 : 1;
  }
  return r;
}

}  // namespace

NodeStepResult integrate_nodes(const NodeIntegrationArgs& a, const ForceSlots& s, size_t begin, size_t end) {
  if (a.f.empty())
    return a.mass_damping > 0.0 ? integrate<true, false>(a, s, begin, end)
                                : integrate<false, false>(a, s, begin, end);
  return a.mass_damping > 0.0 ? integrate<true, true>(a, s, begin, end)
                              : integrate<false, true>(a, s, begin, end);
}

}  // namespace rift::kernels
