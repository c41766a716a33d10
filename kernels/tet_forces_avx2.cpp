// The AVX2 fast path: four consecutive tets per register lane set, through the same law body as the
// scalar reference. A partial group at the end of [begin, end) repeats its last tet in the spare lanes and
// stores only the real ones, so each tet takes the same arithmetic whatever the thread split.
#include "kernels/tet_forces.hpp"

#ifdef __AVX2__

#include <cmath>

#include "kernels/tet_law.hpp"
#include "kernels/tet_simd.hpp"

namespace rift::kernels {

namespace {

struct Group {
  size_t tet[4];                 // tet index per lane (the last real tet repeated in spare lanes)
  int count;                     // real lanes
  V4 ex[3][3], ev[3][3], dm[9];  // position and velocity edges p[c+1] - p[0], Dm^-1
  tet_law::Constants<V4> c;
  V4 sigma0[6];  // initial stress of each lane's material, when there is one
};

template <bool kPrestress>
[[gnu::always_inline]] inline void load_group(const TetForceArgs& a, size_t first, int count, Group& g) {
  g.count = count;
  for (int l = 0; l < 4; ++l) g.tet[l] = first + static_cast<size_t>(l < count ? l : count - 1);
  auto nodes_of_corner = [&](int n, size_t node[4]) {
    for (int l = 0; l < 4; ++l) node[l] = static_cast<size_t>(a.tet_nodes[4 * g.tet[l] + n]);
  };
  size_t node[4];
  nodes_of_corner(0, node);
  V4 x0[3], v0[3], x[3], v[3];
  simd::load_xyz(a.x.data(), node, x0);
  simd::load_xyz(a.v.data(), node, v0);
  for (int n = 1; n < 4; ++n) {
    nodes_of_corner(n, node);
    simd::load_xyz(a.x.data(), node, x);
    simd::load_xyz(a.v.data(), node, v);
    for (int i = 0; i < 3; ++i) {
      g.ex[n - 1][i] = x[i] - x0[i];
      g.ev[n - 1][i] = v[i] - v0[i];
    }
  }
  for (int k = 0; k < 8; k += 2) simd::load_pair(a.dm_inv.data(), 9, k, g.tet, g.dm[k], g.dm[k + 1]);
  g.dm[8] = simd::gather1(a.dm_inv.data() + 8, 9, g.tet);
  g.c.volume0 = simd::gather1(a.volume0.data(), 1, g.tet);
  size_t mat[4];
  const TetMaterial* m[4];
  for (int l = 0; l < 4; ++l) {
    mat[l] = static_cast<size_t>(a.material[g.tet[l]]);
    m[l] = &a.materials[mat[l]];
  }
  g.c.lambda = _mm256_setr_pd(m[0]->lambda, m[1]->lambda, m[2]->lambda, m[3]->lambda);
  g.c.mu = _mm256_setr_pd(m[0]->mu, m[1]->mu, m[2]->mu, m[3]->mu);
  g.c.eta = _mm256_setr_pd(m[0]->eta, m[1]->eta, m[2]->eta, m[3]->eta);
  if (kPrestress)
    for (int k = 0; k < 6; k += 2)
      simd::load_pair(a.initial_stress.data(), 6, k, mat, g.sigma0[k], g.sigma0[k + 1]);
}

// j - ln(1 + j) per lane: the series everywhere, then the few lanes with |j| >= small_j redone exactly as
// the scalar path does (large volumetric strains are rare, so this is almost never taken).
[[gnu::always_inline]] inline V4 excess_log(V4 j) {
  V4 g = tet_law::excess_log_series(j);
  const V4 abs_j = _mm256_andnot_pd(_mm256_set1_pd(-0.0), j);
  const int large = _mm256_movemask_pd(_mm256_cmp_pd(abs_j, _mm256_set1_pd(tet_law::small_j), _CMP_GE_OQ));
  if (large == 0) return g;
  alignas(32) double lanes_j[4], lanes_g[4];
  _mm256_store_pd(lanes_j, j);
  _mm256_store_pd(lanes_g, g);
  for (int l = 0; l < 4; ++l)
    if (large & (1 << l)) lanes_g[l] = lanes_j[l] - std::log1p(lanes_j[l]);
  return _mm256_load_pd(lanes_g);
}

[[gnu::always_inline]] inline void store_group(const TetForceArgs& a, const Group& g, V4 ok,
                                               tet_law::Response<V4>& r) {
  const size_t t = g.tet[0];
  V4 f[12];
  for (int n = 0; n < 12; ++n) f[n] = simd::keep(ok, r.force[n / 3][n % 3]);
  for (int b = 0; b < 3; ++b)
    simd::store_block4(f + 4 * b, a.corner_force.data() + 12 * (t - a.corner_force_first) + 4 * b, 12,
                       g.count);
  if (!a.stress.empty()) {
    for (int n = 0; n < 6; ++n) r.stress[n] = simd::keep(ok, r.stress[n]);
    simd::store_block4(r.stress, a.stress.data() + 6 * t, 6, g.count);
    simd::store_pair(r.stress[4], r.stress[5], a.stress.data() + 6 * t + 4, 6, g.count);
  }
  if (!a.strain_energy.empty()) simd::store1(simd::keep(ok, r.energy), a.strain_energy.data() + t, g.count);
  if (!a.viscous_power.empty()) simd::store1(simd::keep(ok, r.power), a.viscous_power.data() + t, g.count);
}

// Records tets of this group whose J is not > 0 although their reference volume is.
[[gnu::always_inline]] inline void count_inverted(const Group& g, V4 J, TetForceStatus& status) {
  const V4 active = _mm256_cmp_pd(g.c.volume0, _mm256_setzero_pd(), _CMP_GT_OQ);
  const V4 bad = _mm256_andnot_pd(_mm256_cmp_pd(J, _mm256_setzero_pd(), _CMP_GT_OQ), active);
  const int bits = _mm256_movemask_pd(bad) & ((1 << g.count) - 1);
  if (bits == 0) return;
  if (status.inverted == 0) status.first_inverted = static_cast<int64_t>(g.tet[__builtin_ctz(bits)]);
  status.inverted += static_cast<size_t>(__builtin_popcount(bits));
}

// kPrestress: an initial stress is given; without, it is compile-time absent.
template <bool kPrestress>
[[gnu::always_inline]] inline void process_group(const TetForceArgs& a, Group& g, TetForceStatus& status) {
  tet_law::Wanted<V4> want;
  want.energy = !a.strain_energy.empty();
  want.power = !a.viscous_power.empty();
  if (kPrestress) want.sigma0 = g.sigma0;
  tet_law::Kinematics<V4> k;
  tet_law::kinematics(g.ex, g.dm, k);
  count_inverted(g, k.J, status);
  const V4 zero = _mm256_setzero_pd();
  const V4 ok =
      _mm256_and_pd(_mm256_cmp_pd(k.J, zero, _CMP_GT_OQ), _mm256_cmp_pd(g.c.volume0, zero, _CMP_GT_OQ));
  // Rejected lanes continue with J = 1, j = 0 (results discarded) so no lane takes log1p of j <= -1.
  k.J = simd::select(ok, k.J, _mm256_set1_pd(1.0));
  k.j = simd::keep(ok, k.j);
  tet_law::Response<V4> r;
  tet_law::response(k, g.ev, g.dm, g.c, want.energy ? excess_log(k.j) : zero, want, r);
  store_group(a, g, ok, r);
}

template <bool kPrestress>
TetForceStatus forces(const TetForceArgs& args, size_t begin, size_t end) {
  TetForceStatus status;
  Group g;
  for (size_t t = begin; t < end; t += 4) {
    load_group<kPrestress>(args, t, static_cast<int>(end - t < 4 ? end - t : 4), g);
    process_group<kPrestress>(args, g, status);
  }
  return status;
}

}  // namespace

TetForceStatus tet_forces(const TetForceArgs& args, size_t begin, size_t end) {
  return args.initial_stress.empty() ? forces<false>(args, begin, end) : forces<true>(args, begin, end);
}

bool tet_forces_vectorised() {
  return true;
}

}  // namespace rift::kernels

#endif  // __AVX2__
