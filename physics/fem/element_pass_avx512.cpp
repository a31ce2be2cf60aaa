// The SIMD element pass for AVX-512 (8 tets a vector). Only called when the CPU has
// avx512f/dq/vl and fma (elastic_forces.cpp checks); headers come before the target region so
// none of their inline functions is compiled for AVX-512 (they are shared with the scalar code).

#include <immintrin.h>

#include <cmath>

#include "physics/fem/element_batches.h"
#include "physics/fem/element_pass_simd.h"
#include "physics/fem/tangent_blocks.h"

#pragma GCC push_options
#pragma GCC target("avx512f,avx512dq,avx512vl,avx2,fma")

namespace vesica::physics {
namespace element_pass_avx512 {

constexpr int W = 8;
typedef double vd __attribute__((vector_size(64)));
typedef long long vm __attribute__((vector_size(64)));

inline vd Load(const double* p) { return _mm512_loadu_pd(p); }
inline void Store(double* p, vd v) { _mm512_storeu_pd(p, v); }
inline vd Gather(const double* base, const int* idx) {
  // Masked / zero-masked forms: the plain ones leave GCC 12 warning about their undefined source.
  return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), 0xff, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx)),
                                  base, 8);
}
inline vd Sqrt(vd x) { return _mm512_maskz_sqrt_pd(0xff, x); }
// 1 / x and 1 / sqrt(x) from the 14-bit estimates and two Newton steps each (~1 ulp): a 512-bit
// divide or square root holds the divider ~16-20 cycles, and the polar iteration's three were a
// fifth of the pass.
inline vd Reciprocal(vd x) {
  vd r = _mm512_maskz_rcp14_pd(0xff, x);
  for (int step = 0; step < 2; ++step) r = r + r * (1.0 - x * r);
  return r;
}
inline vd ReciprocalSqrt(vd x) {
  vd r = _mm512_maskz_rsqrt14_pd(0xff, x);
  const vd half_x = 0.5 * x;
  for (int step = 0; step < 2; ++step) r = r * (1.5 - half_x * r * r);
  return r;
}
inline bool Any(vm m) { return _mm512_test_epi64_mask(__m512i(m), __m512i(m)) != 0; }
// base[idx[l] + 0..2] of the 8 lanes as x, y, z vectors: each lane's (x, y) by a 128-bit load,
// put together by inserts and two unpacks, and z by one gather (three gathers before).
inline void Gather3(const double* base, const int* idx, vd& x, vd& y, vd& z) {
  const __m512d zero = _mm512_setzero_pd();
  __m512d even = _mm512_insertf64x2(zero, _mm_loadu_pd(base + idx[0]), 0);  // x0 y0 x2 y2 x4 y4 x6 y6
  __m512d odd = _mm512_insertf64x2(zero, _mm_loadu_pd(base + idx[1]), 0);   // x1 y1 x3 y3 x5 y5 x7 y7
  even = _mm512_insertf64x2(even, _mm_loadu_pd(base + idx[2]), 1);
  odd = _mm512_insertf64x2(odd, _mm_loadu_pd(base + idx[3]), 1);
  even = _mm512_insertf64x2(even, _mm_loadu_pd(base + idx[4]), 2);
  odd = _mm512_insertf64x2(odd, _mm_loadu_pd(base + idx[5]), 2);
  even = _mm512_insertf64x2(even, _mm_loadu_pd(base + idx[6]), 3);
  odd = _mm512_insertf64x2(odd, _mm_loadu_pd(base + idx[7]), 3);
  x = _mm512_maskz_unpacklo_pd(0xff, even, odd);
  y = _mm512_maskz_unpackhi_pd(0xff, even, odd);
  z = Gather(base + 2, idx);
}
// The quaternions (x y z w) of 8 consecutive tets, stored one after another, as 4 vectors of
// their components and back: 4 contiguous loads or stores and 8 shuffles instead of 4 gathers
// or 32 scalar stores.
inline void LoadQuaternions(const double* p, vd q[4]) {
  const __m512i first = _mm512_setr_epi64(0, 4, 1, 5, 8, 12, 9, 13),
                second = _mm512_setr_epi64(2, 6, 3, 7, 10, 14, 11, 15);
  const __m512d a = _mm512_loadu_pd(p), b = _mm512_loadu_pd(p + 8), c = _mm512_loadu_pd(p + 16),
                d = _mm512_loadu_pd(p + 24);
  const __m512d ab_low = _mm512_maskz_unpacklo_pd(0xff, a, b);   // x0 x2 z0 z2 x1 x3 z1 z3
  const __m512d ab_high = _mm512_maskz_unpackhi_pd(0xff, a, b);  // y0 y2 w0 w2 y1 y3 w1 w3
  const __m512d cd_low = _mm512_maskz_unpacklo_pd(0xff, c, d);
  const __m512d cd_high = _mm512_maskz_unpackhi_pd(0xff, c, d);
  q[0] = _mm512_maskz_permutex2var_pd(0xff, ab_low, first, cd_low);
  q[1] = _mm512_maskz_permutex2var_pd(0xff, ab_high, first, cd_high);
  q[2] = _mm512_maskz_permutex2var_pd(0xff, ab_low, second, cd_low);
  q[3] = _mm512_maskz_permutex2var_pd(0xff, ab_high, second, cd_high);
}
inline void StoreQuaternions(double* p, const vd q[4]) {
  const __m512i first = _mm512_setr_epi64(0, 2, 8, 10, 1, 3, 9, 11),
                second = _mm512_setr_epi64(4, 6, 12, 14, 5, 7, 13, 15);
  const __m512d ab_low = _mm512_maskz_permutex2var_pd(0xff, q[0], first, q[2]);  // x0 x2 z0 z2 x1 x3 z1 z3
  const __m512d ab_high = _mm512_maskz_permutex2var_pd(0xff, q[1], first, q[3]);
  const __m512d cd_low = _mm512_maskz_permutex2var_pd(0xff, q[0], second, q[2]);
  const __m512d cd_high = _mm512_maskz_permutex2var_pd(0xff, q[1], second, q[3]);
  _mm512_storeu_pd(p, _mm512_maskz_unpacklo_pd(0xff, ab_low, ab_high));
  _mm512_storeu_pd(p + 8, _mm512_maskz_unpackhi_pd(0xff, ab_low, ab_high));
  _mm512_storeu_pd(p + 16, _mm512_maskz_unpacklo_pd(0xff, cd_low, cd_high));
  _mm512_storeu_pd(p + 24, _mm512_maskz_unpackhi_pd(0xff, cd_low, cd_high));
}
// out[idx[l] + 0..2] += (x, y, z) of lane l for l < count, in lane order (a run of lanes with the
// same index summed first). (x_l, y_l) pairs come out
// of two unpacks and six extracts in registers, z through one store: the lanes' stores and
// reloads of a scatter from memory were most of a product's loads.
inline void ScatterAdd3(vd x, vd y, vd z, const int* idx, int count, double* out) {
  // Zero-masked forms, as in Gather: the plain ones leave GCC 12 warning about an undefined source.
  const __m512d even = _mm512_maskz_unpacklo_pd(0xff, x, y);  // x0 y0 x2 y2 x4 y4 x6 y6
  const __m512d odd = _mm512_maskz_unpackhi_pd(0xff, x, y);   // x1 y1 x3 y3 x5 y5 x7 y7
  alignas(64) double zs[8];
  _mm512_store_pd(zs, z);
  // Lane l's (x, y) is 128-bit chunk l / 2 of even (l even) or odd; chunk 0 by its elements, as
  // GCC 12 warns on the cast.
  const __m128d xy[8] = {__m128d{even[0], even[1]},
                         __m128d{odd[0], odd[1]},
                         _mm512_maskz_extractf64x2_pd(3, even, 1),
                         _mm512_maskz_extractf64x2_pd(3, odd, 1),
                         _mm512_maskz_extractf64x2_pd(3, even, 2),
                         _mm512_maskz_extractf64x2_pd(3, odd, 2),
                         _mm512_maskz_extractf64x2_pd(3, even, 3),
                         _mm512_maskz_extractf64x2_pd(3, odd, 3)};
  auto add = [&](int l, __m128d v_xy, double v_z) {
    double* o = out + idx[l];
    _mm_storeu_pd(o, _mm_add_pd(_mm_loadu_pd(o), v_xy));
    o[2] += v_z;
  };
  if (count < 8) {
    for (int l = 0; l < count; ++l) add(l, xy[l], zs[l]);
    return;
  }
  // A run of lanes with one index (the tets of a hexahedron share its corner nodes) is summed in
  // registers and added once: successive read-modify-writes of one node wait for each store to be
  // forwarded. Unrolled, so xy stays in registers.
  __m128d run_xy = xy[0];
  double run_z = zs[0];
#pragma GCC unroll 8
  for (int l = 1; l < 8; ++l) {
    if (idx[l] == idx[l - 1]) {
      run_xy = _mm_add_pd(run_xy, xy[l]);
      run_z += zs[l];
    } else {
      add(l - 1, run_xy, run_z);
      run_xy = xy[l];
      run_z = zs[l];
    }
  }
  add(7, run_xy, run_z);
}

#include "physics/fem/element_pass_kernel.inc"

}  // namespace element_pass_avx512

double ElementPassAvx512(const ElementPassArgs& args) { return element_pass_avx512::ElementPass(args); }
void TangentProductAvx512(const ElementPassArgs& args) { element_pass_avx512::TangentProduct(args); }

}  // namespace vesica::physics

#pragma GCC pop_options
