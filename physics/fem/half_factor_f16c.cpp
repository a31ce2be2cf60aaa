// Half-precision supernodal triangular solves (half_factor.h) for CPUs with F16C, AVX2 and FMA.
// Headers come before the target region so none of their inline functions is compiled for it.

#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "physics/fem/half_factor.h"

namespace vesica::physics {

bool HalfFactorSupported() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("f16c") && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

}  // namespace vesica::physics

#pragma GCC push_options
#pragma GCC target("avx2,fma,f16c")

namespace vesica::physics {
namespace {

inline __m256 Load8(const std::uint16_t* p) { return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))); }
inline float Load1(const std::uint16_t* p) { return _cvtsh_ss(*p); }

// Lanes [0, m) set, m in 0..8.
inline __m256i TailMask(int m) { return _mm256_cmpgt_epi32(_mm256_set1_epi32(m), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)); }

inline float Sum(__m256 v) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  const __m128 t = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(t, _mm_movehdup_ps(t)));
}

// y[0..n) += a * l[0..n)
inline void Axpy(float a, const std::uint16_t* l, float* y, int n) {
  const __m256 va = _mm256_set1_ps(a);
  int i = 0;
  for (; i + 8 <= n; i += 8) _mm256_storeu_ps(y + i, _mm256_fmadd_ps(va, Load8(l + i), _mm256_loadu_ps(y + i)));
  for (; i < n; ++i) y[i] += a * Load1(l + i);
}

// l[0..n) . y[0..n)
inline float Dot(const std::uint16_t* l, const float* y, int n) {
  __m256 acc0 = _mm256_setzero_ps(), acc1 = _mm256_setzero_ps();
  int i = 0;
  for (; i + 16 <= n; i += 16) {
    acc0 = _mm256_fmadd_ps(Load8(l + i), _mm256_loadu_ps(y + i), acc0);
    acc1 = _mm256_fmadd_ps(Load8(l + i + 8), _mm256_loadu_ps(y + i + 8), acc1);
  }
  for (; i + 8 <= n; i += 8) acc0 = _mm256_fmadd_ps(Load8(l + i), _mm256_loadu_ps(y + i), acc0);
  float s = Sum(_mm256_add_ps(acc0, acc1));
  for (; i < n; ++i) s += Load1(l + i) * y[i];
  return s;
}

// y[0..n) += sum_c a[c] l_c[0..n) for C columns l_c = l + c * stride: y is read and written once
// for C columns of L.
template <int C>
inline void AxpyColumns(const float* a, const std::uint16_t* l, std::ptrdiff_t stride, float* y, int n) {
  __m256 coefficient[C];
  for (int c = 0; c < C; ++c) coefficient[c] = _mm256_set1_ps(a[c]);
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    __m256 v = _mm256_loadu_ps(y + i);
    for (int c = 0; c < C; ++c) v = _mm256_fmadd_ps(coefficient[c], Load8(l + c * stride + i), v);
    _mm256_storeu_ps(y + i, v);
  }
  if (i < n) {  // the last 1-7 rows in one masked vector (the factor is padded for the over-read)
    const __m256i mask = TailMask(n - i);
    __m256 v = _mm256_maskload_ps(y + i, mask);
    for (int c = 0; c < C; ++c) v = _mm256_fmadd_ps(coefficient[c], Load8(l + c * stride + i), v);
    _mm256_maskstore_ps(y + i, mask, v);
  }
}

// out[c] = l_c[0..n) . y[0..n) for C columns l_c = l + c * stride: y is read once.
template <int C>
inline void DotColumns(const std::uint16_t* l, std::ptrdiff_t stride, const float* y, int n, float* out) {
  __m256 sum[C];
  for (int c = 0; c < C; ++c) sum[c] = _mm256_setzero_ps();
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 v = _mm256_loadu_ps(y + i);
    for (int c = 0; c < C; ++c) sum[c] = _mm256_fmadd_ps(Load8(l + c * stride + i), v, sum[c]);
  }
  if (i < n) {  // the last 1-7 rows in one masked vector (the factor is padded for the over-read)
    const __m256i mask = TailMask(n - i);
    const __m256 v = _mm256_maskload_ps(y + i, mask);
    for (int c = 0; c < C; ++c)
      sum[c] = _mm256_fmadd_ps(_mm256_and_ps(Load8(l + c * stride + i), _mm256_castsi256_ps(mask)), v, sum[c]);
  }
  for (int c = 0; c < C; ++c) out[c] = Sum(sum[c]);
}

inline void Axpy4(const float* a, const std::uint16_t* l, std::ptrdiff_t stride, float* y, int n) {
  AxpyColumns<4>(a, l, stride, y, n);
}
inline void Dot4(const std::uint16_t* l, std::ptrdiff_t stride, const float* y, int n, float* out) {
  DotColumns<4>(l, stride, y, n, out);
}

}  // namespace

void ConvertToHalfF16c(const double* x, std::size_t n, double scale, std::uint16_t* out) {
  std::size_t k = 0;
  const __m256d s = _mm256_set1_pd(scale);
  for (; k + 8 <= n; k += 8) {
    const __m128 lo = _mm256_cvtpd_ps(_mm256_mul_pd(s, _mm256_loadu_pd(x + k)));
    const __m128 hi = _mm256_cvtpd_ps(_mm256_mul_pd(s, _mm256_loadu_pd(x + k + 4)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + k),
                     _mm256_cvtps_ph(_mm256_set_m128(hi, lo), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
  }
  for (; k < n; ++k) out[k] = _cvtss_sh(static_cast<float>(scale * x[k]), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
}

void HalfFactorSolveF16c(const HalfFactorView& f, float* y, float* gathered) {
  for (int s = 0; s < f.num_supernodes; ++s) {  // L z = y
    const int k0 = f.super[s], nc = f.super[s + 1] - k0, nr = f.pi[s + 1] - f.pi[s];
    const std::uint16_t* l = f.values + f.px[s];
    float* ys = y + k0;
    // Diagonal block, four columns at a time: their 4 x 4 triangle, then the rows below it.
    const int panels = nc / 4 * 4;
    for (int j0 = 0; j0 < panels; j0 += 4) {
      const std::uint16_t* panel = l + static_cast<std::ptrdiff_t>(j0) * nr;
      float minus[4];
      for (int c = 0; c < 4; ++c) {
        const std::uint16_t* column = panel + static_cast<std::ptrdiff_t>(c) * nr + j0;
        ys[j0 + c] /= Load1(column + c);
        for (int r = c + 1; r < 4; ++r) ys[j0 + r] -= Load1(column + r) * ys[j0 + c];
        minus[c] = -ys[j0 + c];
      }
      Axpy4(minus, panel + j0 + 4, nr, ys + j0 + 4, nc - j0 - 4);
    }
    for (int j = panels; j < nc; ++j) {
      const std::uint16_t* column = l + static_cast<std::ptrdiff_t>(j) * nr;
      ys[j] /= Load1(column + j);
      Axpy(-ys[j], column + j + 1, ys + j + 1, nc - j - 1);
    }
    const int below = nr - nc;
    if (below == 0) continue;
    for (int i = 0; i < below; ++i) gathered[i] = 0.0f;
    int j = 0;
    for (; j + 8 <= nc; j += 8) AxpyColumns<8>(ys + j, l + static_cast<std::ptrdiff_t>(j) * nr + nc, nr, gathered, below);
    for (; j + 4 <= nc; j += 4) Axpy4(ys + j, l + static_cast<std::ptrdiff_t>(j) * nr + nc, nr, gathered, below);
    for (; j < nc; ++j) Axpy(ys[j], l + static_cast<std::ptrdiff_t>(j) * nr + nc, gathered, below);
    const int* rows = f.rows + f.pi[s] + nc;
    for (int i = 0; i < below; ++i) y[rows[i]] -= gathered[i];
  }
  for (int s = f.num_supernodes - 1; s >= 0; --s) {  // L^T w = z
    const int k0 = f.super[s], nc = f.super[s + 1] - k0, nr = f.pi[s + 1] - f.pi[s];
    const std::uint16_t* l = f.values + f.px[s];
    float* ys = y + k0;
    const int below = nr - nc;
    if (below > 0) {
      const int* rows = f.rows + f.pi[s] + nc;
      for (int i = 0; i < below; ++i) gathered[i] = y[rows[i]];
      int j = 0;
      for (; j + 8 <= nc; j += 8) {
        float dots[8];
        DotColumns<8>(l + static_cast<std::ptrdiff_t>(j) * nr + nc, nr, gathered, below, dots);
        for (int c = 0; c < 8; ++c) ys[j + c] -= dots[c];
      }
      for (; j + 4 <= nc; j += 4) {
        float dots[4];
        Dot4(l + static_cast<std::ptrdiff_t>(j) * nr + nc, nr, gathered, below, dots);
        for (int c = 0; c < 4; ++c) ys[j + c] -= dots[c];
      }
      for (; j < nc; ++j) ys[j] -= Dot(l + static_cast<std::ptrdiff_t>(j) * nr + nc, gathered, below);
    }
    // Diagonal block transposed: the columns past the last whole panel one by one, then the panels
    // from the last: dots with the solved rows below them, then their 4 x 4 triangle.
    const int panels = nc / 4 * 4;
    for (int j = nc - 1; j >= panels; --j) {
      const std::uint16_t* column = l + static_cast<std::ptrdiff_t>(j) * nr;
      ys[j] = (ys[j] - Dot(column + j + 1, ys + j + 1, nc - j - 1)) / Load1(column + j);
    }
    for (int j0 = panels - 4; j0 >= 0; j0 -= 4) {
      const std::uint16_t* panel = l + static_cast<std::ptrdiff_t>(j0) * nr;
      float dots[4];
      Dot4(panel + j0 + 4, nr, ys + j0 + 4, nc - j0 - 4, dots);
      for (int c = 3; c >= 0; --c) {
        const std::uint16_t* column = panel + static_cast<std::ptrdiff_t>(c) * nr + j0;
        float v = ys[j0 + c] - dots[c];
        for (int r = c + 1; r < 4; ++r) v -= Load1(column + r) * ys[j0 + r];
        ys[j0 + c] = v / Load1(column + c);
      }
    }
  }
}

}  // namespace vesica::physics

#pragma GCC pop_options
