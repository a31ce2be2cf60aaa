// The SIMD element pass for AVX2 (4 tets a vector). Only called when the CPU has avx2 and fma
// (elastic_forces.cpp checks); headers come before the target region so none of their inline
// functions is compiled for AVX2 (they are shared with the scalar code).

#include <immintrin.h>

#include <cmath>

#include "physics/fem/element_batches.h"
#include "physics/fem/element_pass_simd.h"
#include "physics/fem/tangent_blocks.h"

#pragma GCC push_options
#pragma GCC target("avx2,fma")

namespace vesica::physics {
namespace element_pass_avx2 {

constexpr int W = 4;
typedef double vd __attribute__((vector_size(32)));
typedef long long vm __attribute__((vector_size(32)));

inline vd Load(const double* p) { return _mm256_loadu_pd(p); }
inline void Store(double* p, vd v) { _mm256_storeu_pd(p, v); }
inline vd Gather(const double* base, const int* idx) {
  // The masked form with a defined source: the plain one leaves GCC 12 warning about its undefined one.
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, _mm_loadu_si128(reinterpret_cast<const __m128i*>(idx)),
                                  _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8);
}
inline vd Sqrt(vd x) { return _mm256_sqrt_pd(x); }
inline vd Reciprocal(vd x) { return 1.0 / x; }
inline vd ReciprocalSqrt(vd x) { return 1.0 / _mm256_sqrt_pd(x); }
inline bool Any(vm m) { return _mm256_movemask_pd(__m256d(m)) != 0; }
// base[idx[l] + 0..2] of the 4 lanes as x, y, z vectors.
inline void Gather3(const double* base, const int* idx, vd& x, vd& y, vd& z) {
  x = Gather(base, idx);
  y = Gather(base + 1, idx);
  z = Gather(base + 2, idx);
}
// The quaternions (x y z w) of 4 consecutive tets as 4 vectors of their components and back (a
// 4 x 4 transpose either way).
inline void Transpose4x4(const __m256d in[4], vd out[4]) {
  const __m256d t0 = _mm256_unpacklo_pd(in[0], in[1]), t1 = _mm256_unpackhi_pd(in[0], in[1]);
  const __m256d t2 = _mm256_unpacklo_pd(in[2], in[3]), t3 = _mm256_unpackhi_pd(in[2], in[3]);
  out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
  out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
  out[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}
inline void LoadQuaternions(const double* p, vd q[4]) {
  const __m256d rows[4] = {_mm256_loadu_pd(p), _mm256_loadu_pd(p + 4), _mm256_loadu_pd(p + 8), _mm256_loadu_pd(p + 12)};
  Transpose4x4(rows, q);
}
inline void StoreQuaternions(double* p, const vd q[4]) {
  const __m256d columns[4] = {q[0], q[1], q[2], q[3]};
  vd rows[4];
  Transpose4x4(columns, rows);
  for (int k = 0; k < 4; ++k) _mm256_storeu_pd(p + 4 * k, rows[k]);
}
// out[idx[l] + 0..2] += (x, y, z) of lane l for l < count, in lane order (as in the AVX-512 pass).
inline void ScatterAdd3(vd x, vd y, vd z, const int* idx, int count, double* out) {
  const __m256d even = _mm256_unpacklo_pd(x, y);  // x0 y0 x2 y2
  const __m256d odd = _mm256_unpackhi_pd(x, y);   // x1 y1 x3 y3
  alignas(32) double zs[4];
  _mm256_store_pd(zs, z);
  const __m128d xy[4] = {_mm256_castpd256_pd128(even), _mm256_castpd256_pd128(odd), _mm256_extractf128_pd(even, 1),
                         _mm256_extractf128_pd(odd, 1)};
  auto add = [&](int l) {
    double* o = out + idx[l];
    _mm_storeu_pd(o, _mm_add_pd(_mm_loadu_pd(o), xy[l]));
    o[2] += zs[l];
  };
  if (count == 4) {
    add(0), add(1), add(2), add(3);  // unrolled: xy stays in registers
  } else {
    for (int l = 0; l < count; ++l) add(l);
  }
}

#include "physics/fem/element_pass_kernel.inc"

}  // namespace element_pass_avx2

double ElementPassAvx2(const ElementPassArgs& args) { return element_pass_avx2::ElementPass(args); }
void TangentProductAvx2(const ElementPassArgs& args) { element_pass_avx2::TangentProduct(args); }

}  // namespace vesica::physics

#pragma GCC pop_options
