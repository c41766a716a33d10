// The AVX2 fast path of joint_forces: four consecutive joints per register, one joint per lane. The point
// law is joint_law.hpp's, instantiated on the 4-wide lane type (Lanes<V4> below); the geometry and the sums
// over the points are restated lane-wise here with the same expressions in the same order as the scalar
// kernel, so the two paths agree to the compiler's fused multiply-adds (the unit tests compare them on
// random joints in every state).
// A broken or degenerate joint, or a damaged one whose material has residual friction (its slider keeps a
// history), goes through joint_forces_scalar on its own (rare, and broken joints need no law); the other
// lanes of its group keep the vector path's results. A partial group at the end of [begin, end) repeats its
// last joint in the spare lanes and stores only the real ones. So each joint takes the same arithmetic
// whatever its group holds, and whatever the split of the joints between threads or processes.
#include "kernels/joint_forces.hpp"

#ifdef __AVX2__

#include <immintrin.h>

#include <algorithm>
#include <cmath>

#include "kernels/joint_break.hpp"
#include "kernels/tet_simd.hpp"  // V4, gathers and transposing stores

namespace rift::kernels {

// The joint law's lane operations on four joints (joint_law.hpp).
template <>
struct joint_law::Lanes<V4> {
  using Mask = V4;  // all bits set in the lanes where the condition holds
  static V4 splat(double a) { return _mm256_set1_pd(a); }
  static V4 none() { return _mm256_setzero_pd(); }
  static V4 less(V4 a, V4 b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }
  static V4 greater(V4 a, V4 b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }
  static V4 equal(V4 a, V4 b) { return _mm256_cmp_pd(a, b, _CMP_EQ_OQ); }
  static V4 not_positive(V4 a) { return _mm256_cmp_pd(a, _mm256_setzero_pd(), _CMP_NGT_UQ); }  // NaN too
  static V4 both(V4 a, V4 b) { return _mm256_and_pd(a, b); }
  static V4 either(V4 a, V4 b) { return _mm256_or_pd(a, b); }
  static bool any(V4 m) { return _mm256_movemask_pd(m) != 0; }
  static bool all(V4 m) { return _mm256_movemask_pd(m) == 0xF; }
  static V4 select(V4 m, V4 if_true, V4 if_false) { return simd::select(m, if_true, if_false); }
  static V4 keep(V4 m, V4 a) { return simd::keep(m, a); }
  static V4 sqrt(V4 a) { return _mm256_sqrt_pd(a); }
  static V4 max(V4 a, V4 b) { return _mm256_max_pd(a, b); }
  static V4 min(V4 a, V4 b) { return _mm256_min_pd(a, b); }
  // z(D) lane by lane with the scalar function: the exp is only evaluated for damaged points.
  static V4 softening_z(V4 D) {
    alignas(32) double lane_D[4], lane_z[4];
    _mm256_store_pd(lane_D, D);
    for (int l = 0; l < 4; ++l) lane_z[l] = kernels::softening_z(lane_D[l]);
    return _mm256_load_pd(lane_z);
  }
};

namespace {

using L = joint_law::Lanes<V4>;

inline int lanes(V4 mask) {  // one bit per lane
  return _mm256_movemask_pd(mask);
}

struct GeometryV {
  V4 d[3][3];  // d_i = x_i - x_{i+3} (+ the initial offset)
  V4 n[3], area, h, ok;
};

// joint_forces.cpp's geometry(), lane-wise.
void load_geometry(const JointArgs& a, const size_t joint[4], GeometryV& g) {
  V4 xm[3][3];
  for (int i = 0; i < 3; ++i) {
    size_t node_a[4], node_b[4];
    for (int l = 0; l < 4; ++l) {
      node_a[l] = static_cast<size_t>(a.joint_nodes[6 * joint[l] + static_cast<size_t>(i)]);
      node_b[l] = static_cast<size_t>(a.joint_nodes[6 * joint[l] + static_cast<size_t>(i) + 3]);
    }
    V4 xa[3], xb[3];
    simd::load_xyz(a.x.data(), node_a, xa);
    simd::load_xyz(a.x.data(), node_b, xb);
    for (int k = 0; k < 3; ++k) {
      xm[i][k] = 0.5 * (xa[k] + xb[k]);
      g.d[i][k] = xa[k] - xb[k];
    }
  }
  if (!a.initial_offset.empty()) {  // 3 per joint: a node-like record, so load_xyz gathers it
    V4 offset[3];
    simd::load_xyz(a.initial_offset.data(), joint, offset);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) g.d[i][k] = g.d[i][k] + offset[k];
  }
  V4 e1[3], e2[3], e3[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = xm[1][k] - xm[0][k];
    e2[k] = xm[2][k] - xm[0][k];
    e3[k] = xm[2][k] - xm[1][k];
  }
  const V4 c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
  const V4 twice_area = _mm256_sqrt_pd(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  g.ok = L::both(L::greater(twice_area, L::splat(0.0)), L::less(twice_area, L::splat(HUGE_VAL)));
  const V4 inv = simd::keep(g.ok, 1.0 / twice_area);
  for (int k = 0; k < 3; ++k) g.n[k] = c[k] * inv;
  g.area = 0.5 * twice_area;
  auto len2 = [](const V4 e[3]) { return e[0] * e[0] + e[1] * e[1] + e[2] * e[2]; };
  g.h = _mm256_sqrt_pd(_mm256_min_pd(_mm256_min_pd(len2(e1), len2(e2)), len2(e3)));
}

using MaterialV = joint_law::Material<V4>;
using ScalesV = joint_law::Scales<V4>;

MaterialV load_materials(const JointArgs& a, const size_t joint[4]) {
  const JointMaterial* m[4];
  for (int l = 0; l < 4; ++l) m[l] = &a.materials[static_cast<size_t>(a.material[joint[l]])];
  auto field = [&](double JointMaterial::*f) {
    return _mm256_setr_pd(m[0]->*f, m[1]->*f, m[2]->*f, m[3]->*f);
  };
  return {field(&JointMaterial::penalty),
          field(&JointMaterial::tensile_strength),
          field(&JointMaterial::cohesion),
          field(&JointMaterial::tan_friction),
          field(&JointMaterial::G_I),
          field(&JointMaterial::G_II),
          field(&JointMaterial::residual_friction)};
}

struct Sums {  // per-joint accumulators over the points
  V4 F[3][3], mean_o, mean_s, energy, damage, normal, shear, failed, short_any;
  V4 slider;      // some point is damaged and its material has residual friction: the scalar path's job
  int onsets[4];  // per lane: points whose history left 0
};

// Updates the histories of the lanes in `keep` only.
void integrate(const JointArgs& a, const size_t joint[4], int keep, const GeometryV& g, const MaterialV& m,
               const ScalesV& k, double Z, Sums& t) {
  const JointRule& rule = *a.rule;
  const size_t P = static_cast<size_t>(rule.points);
  double* history[4];
  for (int l = 0; l < 4; ++l) history[l] = &a.d_max[P * joint[l]];
  const V4 zero = L::splat(0.0);
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) t.F[i][c] = zero;
  t.mean_o = t.mean_s = t.energy = t.damage = t.normal = t.shear = t.failed = zero;
  t.short_any = k.short_normal;
  t.slider = zero;
  for (int& n : t.onsets) n = 0;
  const V4 has_friction = L::greater(m.residual_friction, zero);
  for (size_t q = 0; q < P; ++q) {
    const double N0 = rule.N[q][0], N1 = rule.N[q][1], N2 = rule.N[q][2], w = rule.w[q];
    V4 d[3], sv[3];
    for (int c = 0; c < 3; ++c) d[c] = N0 * g.d[0][c] + N1 * g.d[1][c] + N2 * g.d[2][c];
    const V4 o = d[0] * g.n[0] + d[1] * g.n[1] + d[2] * g.n[2];
    for (int c = 0; c < 3; ++c) sv[c] = d[c] - o * g.n[c];
    const V4 s = _mm256_sqrt_pd(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
    const V4 d_max = _mm256_setr_pd(history[0][q], history[1][q], history[2][q], history[3][q]);
    joint_law::Point<V4> r = joint_law::point(m, k, a.softening, Z, o, s, d_max);
    joint_law::settle_tractions(r);
    alignas(32) double updated[4];
    _mm256_store_pd(updated, r.d_max);
    for (int l = 0; l < 4; ++l)
      if (keep & (1 << l)) {
        t.onsets[l] += history[l][q] == 0.0 && updated[l] > 0.0;
        history[l][q] = updated[l];
      }
    t.failed += simd::keep(_mm256_cmp_pd(r.d_max, L::splat(1.0), _CMP_GE_OQ), L::splat(1.0));
    t.short_any = L::either(t.short_any, r.short_shear);
    t.slider = L::either(t.slider, L::both(has_friction, L::greater(r.d_max, zero)));
    t.normal += r.normal_part;
    t.shear += r.shear_part;
    t.damage = _mm256_max_pd(t.damage, r.d_max);
    const V4 wA = w * g.area;
    t.mean_o += w * o;
    t.mean_s += w * s;
    t.energy += wA * r.energy;
    V4 traction[3];
    for (int c = 0; c < 3; ++c) traction[c] = r.sigma * g.n[c] + r.tau_per_slip * sv[c];
    const V4 wAN[3] = {wA * N0, wA * N1, wA * N2};
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) t.F[i][c] += wAN[i] * traction[c];
  }
}

// The lanes of `keep` stored; the lanes are the joints joint[0] + l.
void store_lanes(const JointArgs& a, size_t j0, int keep, const V4 f[9], V4 damage, V4 energy,
                 const Sums& t) {
  alignas(32) double v[13][4];
  for (int k = 0; k < 9; ++k) _mm256_store_pd(v[k], f[k]);
  _mm256_store_pd(v[9], t.mean_o);
  _mm256_store_pd(v[10], t.mean_s);
  _mm256_store_pd(v[11], damage);
  _mm256_store_pd(v[12], energy);
  for (int l = 0; l < 4; ++l) {
    if (!(keep & (1 << l))) continue;
    const size_t j = j0 + static_cast<size_t>(l);
    for (int k = 0; k < 9; ++k) a.corner_force[9 * j + static_cast<size_t>(k)] = v[k][l];
    if (!a.opening.empty()) a.opening[j] = v[9][l];
    if (!a.slip.empty()) a.slip[j] = v[10][l];
    if (!a.damage.empty()) a.damage[j] = v[11][l];
    if (!a.stored_energy.empty()) a.stored_energy[j] = v[12][l];
  }
}

// Stores the lanes of `keep`: the first `count` lanes (the fast stores) or some of them (lane by lane).
void store(const JointArgs& a, const size_t joint[4], int count, int keep, Sums& t, JointStatus& status) {
  const size_t j0 = joint[0];
  status.short_softening += static_cast<size_t>(__builtin_popcount(lanes(t.short_any) & keep));
  for (int l = 0; l < 4; ++l)
    if (keep & (1 << l)) status.damage_onsets += static_cast<size_t>(t.onsets[l]);
  const V4 breaks = _mm256_cmp_pd(t.failed, L::splat(a.rule->fail_count), _CMP_GE_OQ);
  const V4 intact = _mm256_xor_pd(breaks, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)));
  V4 f[9];  // side B's corners; side A's are minus these and not stored
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) f[3 * i + c] = simd::keep(intact, t.F[i][c]);
  const V4 damage = simd::select(breaks, L::splat(1.0), t.damage), stored = simd::keep(intact, t.energy);
  if (keep == (1 << count) - 1) {
    if (!a.opening.empty()) simd::store1(t.mean_o, a.opening.data() + j0, count);
    if (!a.slip.empty()) simd::store1(t.mean_s, a.slip.data() + j0, count);
    double* out = a.corner_force.data() + 9 * j0;
    simd::store_block4(f, out, 9, count);
    simd::store_block4(f + 4, out + 4, 9, count);
    alignas(32) double last[4];
    _mm256_store_pd(last, f[8]);
    for (int l = 0; l < count; ++l) out[9 * l + 8] = last[l];
    if (!a.damage.empty()) simd::store1(damage, a.damage.data() + j0, count);
    if (!a.stored_energy.empty()) simd::store1(stored, a.stored_energy.data() + j0, count);
  } else {
    store_lanes(a, j0, keep, f, damage, stored, t);
  }
  const int broke = lanes(breaks) & keep;
  if (broke == 0) return;
  alignas(32) double normal[4], shear[4], energy[4];
  _mm256_store_pd(normal, t.normal);
  _mm256_store_pd(shear, t.shear);
  _mm256_store_pd(energy, t.energy);
  for (int l = 0; l < count; ++l)
    if (broke & (1 << l))
      joint_detail::record_break(a, joint[l],
                                 normal[l] >= shear[l] ? JointBreakMode::tensile : JointBreakMode::shear,
                                 energy[l], status);
}

// The joints of the group that the vector path takes (`keep`); the others, one by one, through the scalar
// path: broken ones, degenerate ones, and those whose residual-friction slider (joint_law.hpp) engages,
// from their state before this call.
void process_group(const JointArgs& a, const size_t joint[4], int count, double Z, JointStatus& status) {
  const int real = (1 << count) - 1;
  int keep = real;
  for (int l = 0; l < count; ++l)
    if (a.broken[joint[l]] != 0) keep &= ~(1 << l);
  if (keep != 0) {
    GeometryV g;
    load_geometry(a, joint, g);
    keep &= lanes(g.ok);
    if (keep != 0) {
      const MaterialV m = load_materials(a, joint);
      const ScalesV k = joint_law::scales(m, g.h, a.softening, Z);
      const bool may_slide = (lanes(L::greater(m.residual_friction, L::splat(0.0))) & keep) != 0;
      const size_t P = static_cast<size_t>(a.rule->points);
      double saved[4][kMaxJointPoints];
      if (may_slide)
        for (int l = 0; l < count; ++l)
          for (size_t q = 0; q < P; ++q) saved[l][q] = a.d_max[P * joint[l] + q];
      Sums t;
      integrate(a, joint, keep, g, m, k, Z, t);
      const int slide = may_slide ? lanes(t.slider) & keep : 0;
      for (int l = 0; l < count; ++l)
        if (slide & (1 << l))
          for (size_t q = 0; q < P; ++q) a.d_max[P * joint[l] + q] = saved[l][q];
      keep &= ~slide;
      if (keep != 0) store(a, joint, count, keep, t, status);
    }
  }
  for (int l = 0; l < count; ++l)
    if ((real & ~keep) & (1 << l)) status += joint_forces_scalar(a, joint[l], joint[l] + 1);
}

}  // namespace

JointStatus joint_forces(const JointArgs& args, size_t begin, size_t end) {
  JointStatus status;
  const double Z = softening_integral();
  for (size_t j = begin; j < end; j += 4) {
    const int count = static_cast<int>(std::min<size_t>(4, end - j));
    size_t joint[4];
    for (int l = 0; l < 4; ++l) joint[l] = j + static_cast<size_t>(std::min(l, count - 1));
    process_group(args, joint, count, Z, status);
  }
  return status;
}

bool joint_forces_vectorised() {
  return true;
}

}  // namespace rift::kernels

#endif  // __AVX2__
