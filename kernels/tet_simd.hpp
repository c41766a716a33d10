#pragma once
// AVX2 helpers for the tet kernels: moving per-tet records (rows) into per-component registers with one
// tet per lane (columns) and back. Internal to kernels/; only included when __AVX2__ is defined.
//
// Why explicit registers and not `omp simd` on the scalar loop: gcc 12 declines to vectorise the element
// loop and clang 14 miscompiled it (performance.md 4.4); __m256d arithmetic with operators is exact
// IEEE lane-wise arithmetic on both compilers.
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

// 4x4 transpose: out[c][l] = in[l][c]. Its own inverse, used for loads and stores alike.
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

// xyz of one node for each lane. A masked load reads exactly 3 doubles, so the last node of an array is safe.
inline void load_xyz(const double* base, const size_t node[4], V4 out[3]) {
  const __m256i three = _mm256_setr_epi64x(-1, -1, -1, 0);
  V4 rows[4], cols[4];
  for (int l = 0; l < 4; ++l) rows[l] = _mm256_maskload_pd(base + 3 * node[l], three);
  transpose4(rows, cols);
  for (int c = 0; c < 3; ++c) out[c] = cols[c];
}

// Four consecutive doubles at base + stride * index[l] + offset, as four components across lanes.
inline void load_block4(const double* base, size_t stride, size_t offset, const size_t index[4], V4 out[4]) {
  V4 rows[4];
  for (int l = 0; l < 4; ++l) rows[l] = _mm256_loadu_pd(base + stride * index[l] + offset);
  transpose4(rows, out);
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
