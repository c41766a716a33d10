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

// The leapfrog update of node n from its forces per source (f[0] tets, f[1] joints, f[2] external, to which
// it adds the node rows), with the work booked into r. Damped is a template argument so
// the undamped pass keeps its instructions (and bits) exactly; WriteForce so the pass without a force
// output has no branch for it. Shared by the slot-list pass and the private-tet pass.
struct Leapfrog {
  double keep, gain;  // the damped update's factors
  explicit Leapfrog(const NodeIntegrationArgs& a) {
    const double half_cdt = 0.5 * a.mass_damping * a.dt;
    keep = (1.0 - half_cdt) / (1.0 + half_cdt);
    gain = a.dt / (1.0 + half_cdt);
  }
};

template <bool Damped, bool WriteForce>
[[gnu::always_inline]] inline void advance_node(const NodeIntegrationArgs& a, const Leapfrog& lf, size_t n,
                                                double f[3][3], NodeStepResult& r) {
  double fc[3] = {0.0, 0.0, 0.0};
  // Two loops, not one through a pointer to fc or f[2], so that both stay in registers.
  for (size_t k = 0; k < a.node_row_count; ++k) {
    const double* row = a.node_rows[k].force.data() + 3 * n;
    if (a.node_rows[k].internal)
      for (int c = 0; c < 3; ++c) fc[c] += row[c];
    else
      for (int c = 0; c < 3; ++c) f[2][c] += row[c];
  }
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
      v = is_free && w > 0.0 ? lf.keep * v_old + lf.gain * (total * w + a.gravity[c])
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

// Node slots k.. of source src, while they belong to it (a node's slots are grouped by source: set-up
// guarantees it), summed into f; returns the first slot past them. Source 1 holds pairs: row e >> 1,
// negated when e is odd.
[[gnu::always_inline]] inline int32_t gather_source(const ForceSlots& s, int src, int32_t k, int32_t k_end,
                                                    double f[3]) {
  double fx = 0.0, fy = 0.0, fz = 0.0;
  const double* base = s.source[src].data();
  if (src == 1) {
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
  f[0] = fx, f[1] = fy, f[2] = fz;
  return k;
}

template <bool Damped, bool WriteForce>
NodeStepResult integrate(const NodeIntegrationArgs& a, const ForceSlots& s, size_t begin, size_t end,
                         NodeStepResult r) {
  const Leapfrog lf(a);
  for (size_t n = begin; n < end; ++n) {
    if (n + kPrefetchAhead < end) prefetch_slots(s, n + kPrefetchAhead);
    // Per source, so the work of each can be booked; three plain loops accumulate in registers.
    double f[3][3];
    int32_t k = s.node_range[2 * n];
    const int32_t k_end = s.node_range[2 * n + 1];
    for (int src = 0; src < 3; ++src) k = gather_source(s, src, k, k_end, f[src]);
    advance_node<Damped, WriteForce>(a, lf, n, f, r);
  }
  return r;
}

// How many tets ahead the private-tet pass prefetches its joints' rows.
constexpr size_t kTetPrefetchAhead = 4;

// The loaded-face rows (source 2) of the 4 nodes from `first` on.
[[gnu::always_inline]] inline void prefetch_loaded_faces(const ForceSlots& s, size_t first) {
  for (size_t n = first; n < first + 4; ++n)
    for (int32_t k = s.node_range[2 * n + 1] - 1; k >= s.node_range[2 * n] && s.slots[k] >= s.first_slot[2];
         --k) {
      const double* row = s.source[2].data() + 3 * (s.slots[k] - s.first_slot[2]);
      __builtin_prefetch(row);
      __builtin_prefetch(row + 2);  // 24 B: may straddle two lines
    }
}

template <bool Damped, bool WriteForce>
NodeStepResult integrate_tets(const NodeIntegrationArgs& a, const PrivateTetForces& p, const ForceSlots& s,
                              size_t begin, size_t end, NodeStepResult r) {
  const Leapfrog lf(a);
  const double* rows = p.joint_rows.data();
  for (size_t e = begin; e < end; ++e) {
    if (e + kTetPrefetchAhead < end) {
      const size_t ahead = e + kTetPrefetchAhead;
      for (int face = 0; face < 4; ++face) {
        const int32_t ref = p.face_joint[4 * ahead + face];
        if (ref < 0) continue;
        __builtin_prefetch(rows + 9 * (ref >> 1));
        __builtin_prefetch(rows + 9 * (ref >> 1) + 8);  // 72 B: may straddle two lines
      }
      // Loaded faces are numbered along the surface, not along the tets: their rows miss without this.
      if (p.loaded[ahead]) prefetch_loaded_faces(s, p.first_node + 4 * (ahead - p.tet_first));
    }
    double f[4][3][3];  // corner, source, component
    const double* tet = p.tet_force.data() + 12 * (e - p.tet_first);
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c) {
        f[k][0][c] = tet[3 * k + c];
        f[k][1][c] = 0.0;
        f[k][2][c] = 0.0;
      }
    for (int face = 0; face < 4; ++face) {
      const int32_t ref = p.face_joint[4 * e + face];
      if (ref < 0) continue;
      const double* row = rows + 9 * (ref >> 1);
      const uint64_t sign = static_cast<uint64_t>(ref & 1) << 63;  // negation flips the sign bit only
      const unsigned corners = p.face_corners[4 * e + face];
      for (int i = 0; i < 3; ++i) {
        double* fk = f[(corners >> (2 * i)) & 3u][1];
        for (int c = 0; c < 3; ++c)
          fk[c] += std::bit_cast<double>(std::bit_cast<uint64_t>(row[3 * i + c]) ^ sign);
      }
    }
    const size_t n0 = p.first_node + 4 * (e - p.tet_first);
    for (int k = 0; k < 4; ++k) {
      const size_t n = n0 + static_cast<size_t>(k);
      if (p.loaded[e]) {  // loaded faces: the node's source-2 slots, after its tet and joint slots
        int32_t j = s.node_range[2 * n];
        const int32_t j_end = s.node_range[2 * n + 1];
        while (j < j_end && s.slots[j] < s.first_slot[2]) ++j;
        gather_source(s, 2, j, j_end, f[k][2]);
      }
      advance_node<Damped, WriteForce>(a, lf, n, f[k], r);
    }
  }
  return r;
}

}  // namespace

NodeStepResult integrate_nodes(const NodeIntegrationArgs& a, const ForceSlots& s, size_t begin, size_t end,
                               const NodeStepResult& so_far) {
  if (a.f.empty())
    return a.mass_damping > 0.0 ? integrate<true, false>(a, s, begin, end, so_far)
                                : integrate<false, false>(a, s, begin, end, so_far);
  return a.mass_damping > 0.0 ? integrate<true, true>(a, s, begin, end, so_far)
                              : integrate<false, true>(a, s, begin, end, so_far);
}

NodeStepResult integrate_private_tets(const NodeIntegrationArgs& a, const PrivateTetForces& p,
                                      const ForceSlots& s, size_t begin, size_t end,
                                      const NodeStepResult& so_far) {
  if (a.f.empty())
    return a.mass_damping > 0.0 ? integrate_tets<true, false>(a, p, s, begin, end, so_far)
                                : integrate_tets<false, false>(a, p, s, begin, end, so_far);
  return a.mass_damping > 0.0 ? integrate_tets<true, true>(a, p, s, begin, end, so_far)
                              : integrate_tets<false, true>(a, p, s, begin, end, so_far);
}

}  // namespace rift::kernels
