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

#include "physics/fem/element_pass_kernel.inc"

}  // namespace element_pass_avx2

double ElementPassAvx2(const ElementPassArgs& args) { return element_pass_avx2::ElementPass(args); }
void TangentProductAvx2(const ElementPassArgs& args) { element_pass_avx2::TangentProduct(args); }

}  // namespace vesica::physics

#pragma GCC pop_options
