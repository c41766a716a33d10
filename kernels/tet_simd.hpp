#pragma once
// AVX2 helpers for the tet kernels: moving per-tet records (rows) into per-component registers with one
// tet per lane (columns) and back. Internal to kernels/; only included when __AVX2__ is defined.
//
// Why explicit registers and not `omp simd` on the scalar loop: gcc 12 declines to vectorise the element
// loop and clang 14 miscompiled it (performance.md 4.4); operators on a 4-wide vector type are plain IEEE
// lane-wise arithmetic on both compilers. The scalar and vector paths are not bit-identical under gcc 12
// -O3 -march=native: gcc contracts a * b + c into fused multiply-adds by default in C++ and does not make the
// same choices in both; they agree to ~1e-12 relative (unit tests). With -ffp-contract=off they agree bit for
// bit, at ~15-20 % of the in-cache throughput (measured, not adopted).
//
// Gathers use 128-bit halves and in-lane unpacks rather than 4-wide row loads + full 4x4 transposes: no load
// reaches past a record (so no masked loads at the end of an array) and fewer cross-lane shuffles.
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "kernels/tet_law.hpp"

namespace rift::kernels {

// Four doubles, one tet per lane. The GCC/Clang vector type itself rather than __m256d, whose may_alias
// attribute is dropped (with a warning) when it is used as a template argument; the two convert freely.
typedef double V4 __attribute__((vector_size(32)));

namespace tet_law {
template <>
inline V4 splat<V4>(double a) {
  return _mm256_set1_pd(a);
}
}  // namespace tet_law

namespace simd {

// 4x4 transpose: out[c][l] = in[l][c] (used to scatter 4 components of 4 lanes as 4 rows).
inline void transpose4(const V4 in[4], V4 out[4]) {
  const V4 t0 = _mm256_unpacklo_pd(in[0], in[1]);  // in0[0] in1[0] in0[2] in1[2]
  const V4 t1 = _mm256_unpackhi_pd(in[0], in[1]);  // in0[1] in1[1] in0[3] in1[3]
  const V4 t2 = _mm256_unpacklo_pd(in[2], in[3]);
  const V4 t3 = _mm256_unpackhi_pd(in[2], in[3]);
  out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
  out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
  out[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}

// xyz of one node for each lane. Built from 128-bit halves: (x, y) and (y, z) of lanes 0|2 and 1|3, so every
// load stays inside the node (no masked loads, none past the end of the array) and the transpose needs only
// in-lane unpacks.
inline void load_xyz(const double* base, const size_t node[4], V4 out[3]) {
  const double* p[4] = {base + 3 * node[0], base + 3 * node[1], base + 3 * node[2], base + 3 * node[3]};
  const V4 xy02 = _mm256_loadu2_m128d(p[2], p[0]);  // x0 y0 x2 y2
  const V4 xy13 = _mm256_loadu2_m128d(p[3], p[1]);
  const V4 yz02 = _mm256_loadu2_m128d(p[2] + 1, p[0] + 1);  // y0 z0 y2 z2
  const V4 yz13 = _mm256_loadu2_m128d(p[3] + 1, p[1] + 1);
  out[0] = _mm256_unpacklo_pd(xy02, xy13);
  out[1] = _mm256_unpackhi_pd(xy02, xy13);
  out[2] = _mm256_unpackhi_pd(yz02, yz13);
}

// Doubles k and k+1 of the records at base + stride * index[l], as two components across lanes.
inline void load_pair(const double* base, size_t stride, size_t k, const size_t index[4], V4& a, V4& b) {
  const V4 r02 = _mm256_loadu2_m128d(base + stride * index[2] + k, base + stride * index[0] + k);
  const V4 r13 = _mm256_loadu2_m128d(base + stride * index[3] + k, base + stride * index[1] + k);
  a = _mm256_unpacklo_pd(r02, r13);
  b = _mm256_unpackhi_pd(r02, r13);
}

inline V4 gather1(const double* base, size_t stride, const size_t index[4]) {
  return _mm256_setr_pd(base[stride * index[0]], base[stride * index[1]], base[stride * index[2]],
                        base[stride * index[3]]);
}

// Components comp[0..3] of lanes 0..count-1 to out + stride * l (4 doubles each).
inline void store_block4(const V4 comp[4], double* out, size_t stride, int count) {
  V4 rows[4];
  transpose4(comp, rows);
  for (int l = 0; l < count; ++l) _mm256_storeu_pd(out + stride * l, rows[l]);
}

// Components a, b of lanes 0..count-1 to out + stride * l (2 doubles each).
inline void store_pair(V4 a, V4 b, double* out, size_t stride, int count) {
  const V4 lo = _mm256_unpacklo_pd(a, b);  // a0 b0 a2 b2
  const V4 hi = _mm256_unpackhi_pd(a, b);  // a1 b1 a3 b3
  const __m128d rows[4] = {_mm256_castpd256_pd128(lo), _mm256_castpd256_pd128(hi),
                           _mm256_extractf128_pd(lo, 1), _mm256_extractf128_pd(hi, 1)};
  for (int l = 0; l < count; ++l) _mm_storeu_pd(out + stride * l, rows[l]);
}

inline void store1(V4 a, double* out, int count) {
  if (count == 4) {
    _mm256_storeu_pd(out, a);
    return;
  }
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, a);
  for (int l = 0; l < count; ++l) out[l] = lanes[l];
}

inline V4 select(V4 mask, V4 if_true, V4 if_false) {
  return _mm256_blendv_pd(if_false, if_true, mask);
}
inline V4 keep(V4 mask, V4 a) {
  return _mm256_and_pd(a, mask);
}

}  // namespace simd
}  // namespace rift::kernels
