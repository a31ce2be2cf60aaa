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

#include "physics/fem/element_pass_kernel.inc"

}  // namespace element_pass_avx512

double ElementPassAvx512(const ElementPassArgs& args) { return element_pass_avx512::ElementPass(args); }
void TangentProductAvx512(const ElementPassArgs& args) { element_pass_avx512::TangentProduct(args); }

}  // namespace vesica::physics

#pragma GCC pop_options
