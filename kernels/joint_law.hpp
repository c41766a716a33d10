#pragma once
// Traction-separation law of the 6-node joint at one integration point (femdem.md 1b: Munjiza/Y3D with
// Guo's Mohr-Coulomb, separate G_I / G_II, and D_max irreversibility), written once for one point (double)
// or four joints' points (the AVX2 kernel); joint_forces.cpp and joint_forces_avx2.cpp call it in their
// inner loops, the tests call the scalar form directly.
//
// Inputs: opening o (> 0 = the sides separate), slip s = |sliding vector| >= 0, the point's D_max so far.
// Lengths, with h = the joint's element size and k = p / h:
//   op = 2 f_t / k (peak opening),  ot = softening_length(f_t, op, G_I)
//   sp = 2 f_s / k (peak slip),     st = softening_length(f_s, sp, G_II)
// Shear strength, Mohr-Coulomb with tension cut-off: sigma_c = k o when o < 0 (compression), then
//   f_s = c - sigma_c tan(phi) in compression, f_s = c otherwise (tension is cut off by f_t).
// Damage, elliptical mixed mode, clamped: Dn = max(0, o - op) / ot, Ds = max(0, s - sp) / st,
//   D = sqrt(Dn^2 + Ds^2),  D_eff = min(1, max(D, D_max)),  the point has failed when D_eff = 1.
//
// Tractions (sigma normal, tension positive; tau shear magnitude along the sliding direction):
//   compression o < 0, always (never damaged):  sigma = k o
//   intact, D_eff = 0 (then o <= op and s <= sp):
//       sigma = f_t (2 x - x^2), x = o / op          tau = f_s (2 y - y^2), y = s / sp
//   damaged, D_eff > 0 ("secant" form, also on the envelope):
//       sigma = kn o,  kn = z(D_eff) f_t / (op + D_eff ot)          (o >= 0)
//       tau   = ks s,  ks = z(D_eff) f_s / (sp + D_eff st)
//             + in compression, residual friction capped at (1 - z(D_eff)) mu_res |sigma|: a slider with
//               a slip history, applied by the kernel (residual_friction() below)
// Pure mode I on the envelope has o = op + D ot, so sigma = z(D) f_t: exactly the Y softening branch, and
// below D_max the same formula is femdem.md's hysteretic rule z_unl = z(D_max)(op + D ot)/(op + D_max ot)
// extended linearly to the origin. Likewise for pure mode II.
//
// Deliberate differences from Y's mixed-mode law, and why:
// * On the mixed-mode envelope Y uses sigma = z(D) f_t whatever the shear share; here sigma = kn o, which is
//   smaller when both modes are active (o - op < D ot). With D_max as the only history, Y's form cannot be
//   unloaded along a secant without a traction jump on every unload/reload; the secant form T = K(D_eff) d
//   is continuous everywhere except at damage onset (below) and dissipates -1/2 d.dK.d >= 0 for any path.
// * At damage onset in mixed mode, the mode still below its peak switches from f (2y - y^2) to the secant
//   f y: a drop of at most f/4 (at y = 1/2), none in pure modes. The energy lost is counted as dissipated.
// * Residual friction (default mu_res = 0, Y3D has none) reaches the Y hydro variant's tau -> mu_res |sigma|
//   as z -> 0, but as Coulomb friction with a slip history (an anchor per point), not elastic in s as in
//   Y: that form stored energy in proportion to the slip and handed it back when the compression rose
//   (until 2026-12-02; residual_friction() says how it broke up the wedge scene). Once the joint has
//   broken, the contact model's friction takes over.
//
// Stored (recoverable) energy per unit area, exactly the potential of the tractions at fixed D_max and
// fixed f_s:  compression 1/2 k o^2;  intact f_t op (x^2 - x^3/3) + f_s sp (y^2 - y^3/3);  damaged
// 1/2 kn o^2 + 1/2 ks s^2 (+ the residual slider's spring, residual_friction()).
// Under compression f_s (hence tau) depends on o while sigma does not depend on s, so the law is not
// conservative there: a closed path in (o, s), counter-clockwise, does the net work on the joint
// oint tau ds = -k tan(phi) x (integral of (s/sp)^2 over the enclosed area) (pre-peak, from dtau/do at
// fixed s), and the opposite when travelled the other way. It is
// small (second order in s/sp, zero at zero slip) but it is not friction: the engine's "work - stored"
// books it as dissipated, and it can be negative on such loops. At fixed opening, or without compression,
// the law is exactly conservative at fixed D_max.
#include <algorithm>
#include <cmath>

#include "kernels/softening.hpp"

namespace rift::kernels {

// The law is written once, for a lane type T: double (the scalar reference, one point) or a 4-wide vector
// (joint_forces_avx2.cpp: one joint per lane). Branches become masks and blends: both sides of a branch
// are computed and the lanes pick theirs, except where every lane takes the same side (the compression,
// the confined softening length, the mixed-mode root and the softened branch are only evaluated when some
// lane needs them). For double the masks are bools, so the reference takes exactly its own branch.
// Lanes<T> supplies the operations that differ: comparisons (masks), blends, sqrt, min and max, z(D).
namespace joint_law {

template <class T>
struct Lanes;

template <>
struct Lanes<double> {
  using Mask = bool;
  static double splat(double a) { return a; }
  static bool none() { return false; }
  static bool less(double a, double b) { return a < b; }
  static bool greater(double a, double b) { return a > b; }
  static bool equal(double a, double b) { return a == b; }
  static bool not_positive(double a) { return !(a > 0.0); }  // NaN included
  static bool both(bool a, bool b) { return a && b; }
  static bool either(bool a, bool b) { return a || b; }
  static bool any(bool m) { return m; }
  static bool all(bool m) { return m; }
  static double select(bool m, double if_true, double if_false) { return m ? if_true : if_false; }
  static bool select(bool m, bool if_true, bool if_false) { return m ? if_true : if_false; }
  static double keep(bool m, double a) { return m ? a : 0.0; }
  static double sqrt(double a) { return std::sqrt(a); }
  // As the vector instructions (maxpd, minpd): the second operand when either is NaN; inline, where
  // std::fmax is a call.
  static double max(double a, double b) { return a > b ? a : b; }
  static double min(double a, double b) { return a < b ? a : b; }
  static double softening_z(double D) { return kernels::softening_z(D); }
};

template <class T>
struct Material {
  T penalty;                  // p [Pa]; the joint's stiffness per unit area is p / h
  T tensile_strength;         // f_t [Pa]
  T cohesion;                 // c [Pa]
  T tan_friction;             // tan(phi) of the Mohr-Coulomb envelope
  T G_I, G_II;                // fracture energies [J/m2]
  T residual_friction = T{};  // mu_res, shear transmitted by a fully softened point in compression
};

// What depends on the joint (h, material) but not on the point; the inverses spare per-point divisions.
template <class T>
struct Scales {
  using Mask = typename Lanes<T>::Mask;
  T stiffness;                      // k = p / h [Pa/m]
  T compliance2;                    // 2 / k: peak separation per unit strength [m/Pa]
  T op, ot, inv_op, inv_ot;         // normal peak opening and softening length [m]
  T sp0, st0, inv_sp0, inv_st0;     // shear peak slip and softening length at f_s = c (no confinement)
  Mask short_normal, short_shear0;  // an energy_exact length was floored
};

template <class T>
struct Point {
  using Mask = typename Lanes<T>::Mask;
  T sigma;                    // normal traction, tension positive [Pa]
  T tau;                      // shear traction magnitude (acts along the sliding direction) [Pa], >= 0
  T tau_per_slip;             // tau / s, finite at s = 0: the traction vector is sigma n + this x sv
  T d_max;                    // updated history in [0, 1]; 1 = this point has failed
  T energy;                   // stored energy per unit area [J/m2]
  T normal_part, shear_part;  // Dn^2 and Ds^2: which mode drives the damage (break classification)
  T residual_cap;             // damaged and compressed: (1 - z) mu_res |sigma| (residual_friction())
  Mask short_shear;           // the shear softening length was floored at this confinement
};

}  // namespace joint_law

using JointMaterial = joint_law::Material<double>;
using JointScales = joint_law::Scales<double>;
using JointPointResponse = joint_law::Point<double>;

// When an energy_exact length comes out <= 0 (G too small for this p and h), it is replaced by this
// fraction of the peak separation: practically a brittle drop right after the peak. The event is counted
// (JointStatus::short_softening); joint_min_penalty in softening.hpp tells the user what p would do.
inline constexpr double kBrittleSofteningFraction = 1e-3;

namespace joint_law {

// The softening length (softening.hpp), floored, and flagged in short_length, where energy_exact has none.
template <class T>
[[gnu::always_inline]] inline T floored_length(Softening rule, T f, T peak, T G, double Z,
                                               typename Lanes<T>::Mask& short_length) {
  using L = Lanes<T>;
  const T length = softening_length(rule, f, peak, G, Z, L::max);
  short_length = L::not_positive(length);
  return L::select(short_length, kBrittleSofteningFraction * peak, length);
}

template <class T>
[[gnu::always_inline]] inline Scales<T> scales(const Material<T>& m, T h, Softening rule, double Z) {
  Scales<T> k;
  k.stiffness = m.penalty / h;
  k.compliance2 = 2.0 * h / m.penalty;
  k.op = m.tensile_strength * k.compliance2;
  k.inv_op = 0.5 * k.stiffness / m.tensile_strength;
  k.ot = floored_length(rule, m.tensile_strength, k.op, m.G_I, Z, k.short_normal);
  k.inv_ot = 1.0 / k.ot;
  k.sp0 = m.cohesion * k.compliance2;
  k.inv_sp0 = 0.5 * k.stiffness / m.cohesion;
  k.st0 = floored_length(rule, m.cohesion, k.sp0, m.G_II, Z, k.short_shear0);
  k.inv_st0 = 1.0 / k.st0;
  return k;
}

// The point law (the header's comment): o the opening, s the slip, d_max the point's history.
template <class T>
inline Point<T> point(const Material<T>& m, const Scales<T>& k, Softening rule, double Z, T o, T s, T d_max) {
  using L = Lanes<T>;
  const T zero = L::splat(0.0);
  // Normal compression first: it raises the shear strength (Mohr-Coulomb).
  const auto comp = L::less(o, zero);
  const T sigma_c = L::keep(comp, k.stiffness * o);
  const bool any_comp = L::any(comp);
  const T fs = any_comp ? L::select(comp, m.cohesion - sigma_c * m.tan_friction, m.cohesion) : m.cohesion;
  const T sp = any_comp ? L::select(comp, fs * k.compliance2, k.sp0) : k.sp0;
  const T inv_sp = any_comp ? L::select(comp, 1.0 / sp, k.inv_sp0) : k.inv_sp0;
  // The confined softening length costs two divisions and matters only past the peak slip or once damaged;
  // a compressed point has Dn = 0, so it is needed exactly where s > sp or D_max > 0, known before D.
  T st = k.st0, inv_st = k.inv_st0;
  auto short_confined = L::none();
  const auto needed = L::both(comp, L::either(L::greater(s, sp), L::greater(d_max, zero)));
  if (L::any(needed)) {
    const T st_confined = floored_length(rule, fs, sp, m.G_II, Z, short_confined);
    st = L::select(comp, st_confined, k.st0);
    inv_st = L::select(comp, 1.0 / st_confined, k.inv_st0);
  }

  Point<T> r;
  const T Dn = L::keep(L::greater(o, k.op), (o - k.op) * k.inv_ot);
  const T Ds = L::keep(L::greater(s, sp), (s - sp) * inv_st);
  r.normal_part = Dn * Dn;
  r.shear_part = Ds * Ds;
  const auto mixed = L::both(L::greater(Dn, zero), L::greater(Ds, zero));
  T D = Dn + Ds;  // the square root (long latency) only where both modes are active
  if (L::any(mixed)) D = L::select(mixed, L::sqrt(r.normal_part + r.shear_part), D);
  const T De = L::min(L::max(D, d_max), L::splat(1.0));
  r.d_max = De;
  r.short_shear = L::select(needed, short_confined, k.short_shear0);
  r.residual_cap = zero;

  // Intact, D_eff = 0: the hardening curves, nonlinear elastic.
  const T x = o * k.inv_op;
  r.sigma = L::select(comp, sigma_c, m.tensile_strength * x * (2.0 - x));
  const T normal_energy =
      L::select(comp, 0.5 * sigma_c * o, m.tensile_strength * k.op * x * x * (1.0 - x / 3.0));
  const T y = s * inv_sp;
  r.tau_per_slip = fs * (2.0 - y) * inv_sp;
  r.tau = r.tau_per_slip * s;
  r.energy = normal_energy + fs * sp * y * y * (1.0 - y / 3.0);
  const auto intact = L::equal(De, zero);
  if (L::all(intact)) return r;

  // Damaged, D_eff > 0: the secant form.
  const T z = L::softening_z(De);
  const T sigma = L::select(comp, sigma_c, z * m.tensile_strength / (k.op + De * k.ot) * o);
  const T tau_per_slip = z * fs / (sp + De * st);
  const T tau = tau_per_slip * s;
  r.sigma = L::select(intact, r.sigma, sigma);
  r.tau_per_slip = L::select(intact, r.tau_per_slip, tau_per_slip);
  r.tau = L::select(intact, r.tau, tau);
  r.energy = L::select(intact, r.energy, 0.5 * (sigma * o + tau * s));
  r.residual_cap = L::select(intact, zero, L::keep(comp, (1.0 - z) * m.residual_friction * (zero - sigma_c)));
  return r;
}

// The kernels take sigma and tau / s as finished values before forming the traction sigma n + (tau / s) sv:
// the empty asm statement (no instruction) keeps the compiler from folding the law's last operations into
// the traction's multiply-adds where the law is inlined, which moves about half the joints' forces by an
// ulp and with them every state hash (scripts/state_hashes.py). With it the rounding is the same whether
// or not the law is inlined.
template <class T>
[[gnu::always_inline]] inline void settle_tractions(Point<T>& r) {
  asm("" : "+x"(r.sigma), "+x"(r.tau_per_slip));
}

}  // namespace joint_law

// The scalar reference (tests, the scalar kernel, the joints a vector group hands back).
inline JointScales joint_scales(const JointMaterial& m, double h, Softening rule, double Z) {
  return joint_law::scales(m, h, rule, Z);
}

inline JointPointResponse joint_point_response(const JointMaterial& m, const JointScales& k, Softening rule,
                                               double Z, double o, double s, double d_max) {
  return joint_law::point(m, k, rule, Z, o, s, d_max);
}

// Residual friction at one damaged point (femdem.md 1b, the Y hydro variant's tau -> mu_res |sigma|): a
// Coulomb slider with a stick spring. The traction is k_r (sv - anchor), projected onto the joint's plane
// and capped at `cap` = (1 - z) mu_res |sigma| (JointPointResponse::residual_cap, 0 in tension); past the
// cap the anchor follows the slip, so the friction dissipates what it does beyond its spring. The stored
// energy, |t|^2 / (2 k_r), is bounded by cap^2 / (2 k_r) whatever the slip. k_r = k / 2: with the softened
// shear stiffness (at most z k / 2) the point is never stiffer than the intact k, so the joint's step bound
// holds. Why not the Y form (elastic in the slip, tau = cap along it): its energy grows with the slip and
// follows the compression, so a joint that slips while lightly pressed and slides back while pressed
// harder gains energy; in the wedge scene that pumped the notch-tip zone to pieces (docs/speed-accuracy.md).
// anchor (3, in/out, global frame); t (3, out) is added to the point's traction. Returns the stored energy
// per unit area; what the slider dissipates is booked with the joints' (fracture_dissipation).
inline double residual_friction(double cap, double k_r, const double sv[3], const double n[3],
                                double anchor[3], double t[3]) {
  double e[3];
  for (int c = 0; c < 3; ++c) e[c] = sv[c] - anchor[c];
  const double en = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
  for (int c = 0; c < 3; ++c) e[c] -= en * n[c];
  const double stretch = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  if (k_r * stretch > cap) {  // slipping (stretch > 0 here): the spring keeps its reach cap / k_r
    const double scale = cap / k_r / stretch;
    for (int c = 0; c < 3; ++c) {
      e[c] *= scale;
      anchor[c] = sv[c] - e[c];
    }
  }
  for (int c = 0; c < 3; ++c) t[c] = k_r * e[c];
  return 0.5 * k_r * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
}

}  // namespace rift::kernels
