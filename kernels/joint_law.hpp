#pragma once
// Traction-separation law of the 6-node joint at one integration point (femdem.md 1b: Munjiza/Y3D with
// Guo's Mohr-Coulomb, separate G_I / G_II, and D_max irreversibility). Inline: joint_forces.cpp calls it in
// its inner loop, the tests call it directly.
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

struct JointMaterial {
  double penalty;                  // p [Pa]; the joint's stiffness per unit area is p / h
  double tensile_strength;         // f_t [Pa]
  double cohesion;                 // c [Pa]
  double tan_friction;             // tan(phi) of the Mohr-Coulomb envelope
  double G_I, G_II;                // fracture energies [J/m2]
  double residual_friction = 0.0;  // mu_res, shear transmitted by a fully softened point in compression
};

// When an energy_exact length comes out <= 0 (G too small for this p and h), it is replaced by this
// fraction of the peak separation: practically a brittle drop right after the peak. The event is counted
// (JointStatus::short_softening); joint_min_penalty in softening.hpp tells the user what p would do.
inline constexpr double kBrittleSofteningFraction = 1e-3;

// What depends on the joint (h, material) but not on the point; the inverses spare per-point divisions.
struct JointScales {
  double stiffness;                   // k = p / h [Pa/m]
  double compliance2;                 // 2 / k: peak separation per unit strength [m/Pa]
  double op, ot, inv_op, inv_ot;      // normal peak opening and softening length [m]
  double sp0, st0, inv_sp0, inv_st0;  // shear peak slip and softening length at f_s = c (no confinement)
  bool short_normal, short_shear0;    // an energy_exact length was floored
};

// Softening length, floored (and flagged) when energy_exact has none; see kBrittleSofteningFraction.
inline double floored_length(Softening rule, double f, double peak, double G, double Z, bool& short_length) {
  const double L = softening_length(rule, f, peak, G, Z);
  short_length = !(L > 0.0);
  return short_length ? kBrittleSofteningFraction * peak : L;
}

inline JointScales joint_scales(const JointMaterial& m, double h, Softening rule, double Z) {
  JointScales k;
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

struct JointPointResponse {
  double sigma;                    // normal traction, tension positive [Pa]
  double tau;                      // shear traction magnitude (acts along the sliding direction) [Pa], >= 0
  double tau_per_slip;             // tau / s, finite at s = 0: the traction vector is sigma n + this x sv
  double d_max;                    // updated history in [0, 1]; 1 = this point has failed
  double energy;                   // stored energy per unit area [J/m2]
  double normal_part, shear_part;  // Dn^2 and Ds^2: which mode drives the damage (break classification)
  double residual_cap;             // damaged and compressed: (1 - z) mu_res |sigma| (residual_friction())
  bool short_shear;                // the shear softening length was floored at this confinement
};

inline JointPointResponse joint_point_response(const JointMaterial& m, const JointScales& k, Softening rule,
                                               double Z, double o, double s, double d_max) {
  JointPointResponse r{};
  // Normal compression first: it raises the shear strength.
  const double sigma_c = o < 0.0 ? k.stiffness * o : 0.0;
  double fs = m.cohesion, sp = k.sp0, st = k.st0, inv_sp = k.inv_sp0, inv_st = k.inv_st0;
  r.short_shear = k.short_shear0;
  // The confined softening length costs two divisions and only matters past the peak slip or once damaged,
  // so it is computed when first needed (and only then checked for being too short).
  bool confined_length_pending = false;
  if (sigma_c < 0.0) {
    fs = m.cohesion - sigma_c * m.tan_friction;
    sp = fs * k.compliance2;
    inv_sp = 1.0 / sp;
    confined_length_pending = true;
  }
  auto confined_length = [&] {
    if (!confined_length_pending) return;
    st = floored_length(rule, fs, sp, m.G_II, Z, r.short_shear);
    inv_st = 1.0 / st;
    confined_length_pending = false;
  };
  const double Dn = o > k.op ? (o - k.op) * k.inv_ot : 0.0;
  double Ds = 0.0;
  if (s > sp) {
    confined_length();
    Ds = (s - sp) * inv_st;
  }
  r.normal_part = Dn * Dn;
  r.shear_part = Ds * Ds;
  const double D = (Dn > 0.0 && Ds > 0.0) ? std::sqrt(r.normal_part + r.shear_part) : Dn + Ds;
  const double De = std::min(1.0, std::max(D, d_max));
  r.d_max = De;

  if (De == 0.0) {  // intact: the hardening curves, nonlinear elastic
    if (o < 0.0) {
      r.sigma = sigma_c;
      r.energy = 0.5 * sigma_c * o;
    } else {
      const double x = o * k.inv_op;
      r.sigma = m.tensile_strength * x * (2.0 - x);
      r.energy = m.tensile_strength * k.op * x * x * (1.0 - x / 3.0);
    }
    const double y = s * inv_sp;
    r.tau_per_slip = fs * (2.0 - y) * inv_sp;
    r.tau = r.tau_per_slip * s;
    r.energy += fs * sp * y * y * (1.0 - y / 3.0);
    return r;
  }

  confined_length();
  const double z = softening_z(De);
  r.sigma = o < 0.0 ? sigma_c : z * m.tensile_strength / (k.op + De * k.ot) * o;
  r.tau_per_slip = z * fs / (sp + De * st);
  r.tau = r.tau_per_slip * s;
  r.energy = 0.5 * (r.sigma * o + r.tau * s);
  if (sigma_c < 0.0) r.residual_cap = (1.0 - z) * m.residual_friction * (-sigma_c);
  return r;
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
