// Half-precision supernodal triangular solves (half_factor.h) for CPUs with F16C, AVX2 and FMA.
// Headers come before the target region so none of their inline functions is compiled for it.

#include <immintrin.h>

#include <algorithm>
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

// 8 floats a vector. (A 16-float AVX-512 build of these kernels measured the same on the
// development machine: conversions and multiply-adds are not what limits them.)
constexpr int W = 8;
using vf = __m256;
inline vf LoadHalf(const std::uint16_t* p) {
  return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
inline vf Load(const float* p) { return _mm256_loadu_ps(p); }
inline void Store(float* p, vf v) { _mm256_storeu_ps(p, v); }
inline vf Zero() { return _mm256_setzero_ps(); }
inline vf Splat(float a) { return _mm256_set1_ps(a); }
inline vf Fma(vf a, vf b, vf c) { return _mm256_fmadd_ps(a, b, c); }
inline float Sum(vf v) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  const __m128 t = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(t, _mm_movehdup_ps(t)));
}
// Lanes [0, m) set, m in 0..8: the last rows of a column in one masked vector (LoadHalf may read
// past a column's end: into the next column or the factor's padding).
using Tail = __m256i;
inline Tail MakeTail(int m) {
  return _mm256_cmpgt_epi32(_mm256_set1_epi32(m), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}
inline vf LoadTail(const float* p, Tail mask) { return _mm256_maskload_ps(p, mask); }
inline void StoreTail(float* p, Tail mask, vf v) { _mm256_maskstore_ps(p, mask, v); }
inline vf KeepTail(vf v, Tail mask) { return _mm256_and_ps(v, _mm256_castsi256_ps(mask)); }

// Software prefetch a fixed distance ahead of the solve in the factor's values, paced by the bytes
// the kernels read. Each solve streams the whole factor from L3 (6.4 MB for the SOFA beam, 4.3 MB for
// the 2,900-node box: more than L2), and the hardware prefetchers, which stop at 4 KB pages and
// follow up to eight interleaved column streams, left the solve at ~20 GB/s against ~30 for a plain
// stream. The solve reads the factor in ascending order (forward) and descending supernodes
// (backward), in both cases nearly in order within a supernode, so a cursor ahead of the current
// supernode covers it. 64 KB (prefetched into L1, kept in L2 when L1 drops it) measured best
// among 4 KB ... 256 KB, and better than prefetching to L2 only; the non-temporal hint made the
// solve 2.5x slower (its lines leave L3 too, and the next solve reads them from memory).
class FactorPrefetch {
 public:
  static constexpr std::ptrdiff_t kDistanceBytes = 64 * 1024;

  FactorPrefetch(const std::uint16_t* values, std::size_t entries)
      : values_(reinterpret_cast<const char*>(values)),
        size_(static_cast<std::ptrdiff_t>(entries * sizeof(std::uint16_t))) {}

  // The solve moves on to a supernode whose values start at entry `first` (forward) or end before
  // entry `last` (backward): keep the cursor at least the distance ahead of it.
  void StartForward(std::size_t first) {
    next_ = std::max(next_, Bytes(first) + kDistanceBytes);
    step_ = 64;
  }
  void StartBackward(std::size_t last) {
    next_ = std::min(next_, Bytes(last) - kDistanceBytes);
    step_ = -64;
  }
  // The kernel has read `bytes` more of the factor: prefetch as many bytes further ahead.
  void Consume(std::ptrdiff_t bytes) {
    for (budget_ += bytes; budget_ >= 64; budget_ -= 64, next_ += step_)
      if (next_ >= 0 && next_ < size_) _mm_prefetch(values_ + next_, _MM_HINT_T0);
  }

 private:
  static std::ptrdiff_t Bytes(std::size_t entries) {
    return static_cast<std::ptrdiff_t>(entries * sizeof(std::uint16_t));
  }
  const char* values_;
  std::ptrdiff_t size_;
  std::ptrdiff_t next_ = 0;  // byte offset of the next line to prefetch
  std::ptrdiff_t step_ = 64;
  std::ptrdiff_t budget_ = 0;
};

// Row i of column j of a packed supernode (half_factor.h) is Column(l, nr, j)[i], for i >= j.
inline const std::uint16_t* Column(const std::uint16_t* l, int nr, int j) {
  return l + static_cast<std::ptrdiff_t>(j) * nr - static_cast<std::ptrdiff_t>(j) * (j + 1) / 2;
}

// Lane k of v moved to lane k + shift; lanes outside [shift, end) zeroed.
inline vf ShiftIntoRange(vf v, int shift, int end) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i keep = _mm256_and_si256(_mm256_cmpgt_epi32(lane, _mm256_set1_epi32(shift - 1)),
                                        _mm256_cmpgt_epi32(_mm256_set1_epi32(end), lane));
  const vf moved = _mm256_permutevar8x32_ps(v, _mm256_sub_epi32(lane, _mm256_set1_epi32(shift)));
  return _mm256_and_ps(moved, _mm256_castsi256_ps(keep));
}

// y[j..nr) += sum_c a[c] L_{j+c}, the C columns from j of a packed supernode (C <= 8): their own
// triangle (rows j..j+C-1) as one vector, the column starts moved into place in registers, then
// the rows below it, y read and written once for the C columns. y has a vector's room past nr
// (the triangle's vector may reach past it, adding zeros).
template <int C>
inline void AxpyGroup(const float* a, const std::uint16_t* l, int nr, int j, float* y, FactorPrefetch& prefetch) {
  vf coefficient[C];
  const std::uint16_t* column[C];
  vf top = Zero();
  for (int c = 0; c < C; ++c) {
    coefficient[c] = Splat(a[c]);
    column[c] = Column(l, nr, j + c);
    top = Fma(coefficient[c], ShiftIntoRange(LoadHalf(column[c] + j + c), c, C), top);
  }
  Store(y + j, Load(y + j) + top);
  const int row = j + C, n = nr - row;
  for (int c = 0; c < C; ++c) column[c] += row;
  float* yb = y + row;
  int i = 0;
  for (; i + W <= n; i += W) {
    vf v = Load(yb + i);
    for (int c = 0; c < C; ++c) v = Fma(coefficient[c], LoadHalf(column[c] + i), v);
    Store(yb + i, v);
    prefetch.Consume(C * W * sizeof(std::uint16_t));
  }
  if (i < n) {  // the last rows in one masked vector
    const Tail mask = MakeTail(n - i);
    vf v = LoadTail(yb + i, mask);
    for (int c = 0; c < C; ++c) v = Fma(coefficient[c], LoadHalf(column[c] + i), v);
    StoreTail(yb + i, mask, v);
  }
}

// out[c] = L_{j+c}[j+c..nr) . y[j+c..nr) for the C columns from j of a packed supernode, y read
// once; y has a vector's room past nr, finite.
template <int C>
inline void DotGroup(const std::uint16_t* l, int nr, int j, const float* y, float* out, FactorPrefetch& prefetch) {
  vf sum[C];
  const std::uint16_t* column[C];
  for (int c = 0; c < C; ++c) {  // the triangle: rows j+c..j+C-1 of column j+c
    column[c] = Column(l, nr, j + c);
    sum[c] = KeepTail(LoadHalf(column[c] + j + c) * Load(y + j + c), MakeTail(C - c));
  }
  const int row = j + C, n = nr - row;
  for (int c = 0; c < C; ++c) column[c] += row;
  const float* yb = y + row;
  int i = 0;
  for (; i + W <= n; i += W) {
    const vf v = Load(yb + i);
    for (int c = 0; c < C; ++c) sum[c] = Fma(LoadHalf(column[c] + i), v, sum[c]);
    prefetch.Consume(C * W * sizeof(std::uint16_t));
  }
  if (i < n) {  // the last rows in one masked vector
    const Tail mask = MakeTail(n - i);
    const vf v = LoadTail(yb + i, mask);
    for (int c = 0; c < C; ++c) sum[c] = Fma(KeepTail(LoadHalf(column[c] + i), mask), v, sum[c]);
  }
  for (int c = 0; c < C; ++c) out[c] = Sum(sum[c]);
}

// group.template operator()<C>(j) for the columns [0, nc) in groups of C = 8, then 4, then the
// last 1-3 together: each group's rows are read and written once.
template <typename Group>
inline void ForColumnGroups(int nc, Group&& group) {
  int j = 0;
  for (; j + 8 <= nc; j += 8) group.template operator()<8>(j);
  for (; j + 4 <= nc; j += 4) group.template operator()<4>(j);
  switch (nc - j) {
    case 3:
      group.template operator()<3>(j);
      break;
    case 2:
      group.template operator()<2>(j);
      break;
    case 1:
      group.template operator()<1>(j);
      break;
    default:
      break;
  }
}

}  // namespace

void HalfFactorSolveF16c(const HalfFactorView& f, float* y, float* gathered) {
  FactorPrefetch prefetch(f.values, f.px[f.num_supernodes]);
  // Copies: y's stores could alias the view's floats, and the loops would re-read them.
  const float t_unscale = f.triangle_unscale, b_unscale = f.below_unscale;
  for (int s = 0; s < f.num_supernodes; ++s) {  // L z = y: z_D = T y_D, y_B -= W y_D
    const int k0 = f.super[s], nc = f.super[s + 1] - k0, nr = f.pi[s + 1] - f.pi[s];
    const std::uint16_t* l = f.values + f.px[s];
    prefetch.StartForward(f.px[s]);
    float* ys = y + k0;
    for (int i = 0; i < nr; ++i) gathered[i] = 0.0f;
    ForColumnGroups(nc, [&]<int C>(int j) { AxpyGroup<C>(ys + j, l, nr, j, gathered, prefetch); });
    for (int i = 0; i < nc; ++i) ys[i] = t_unscale * gathered[i];
    const int* rows = f.rows + f.pi[s];
    for (int i = nc; i < nr; ++i) y[rows[i]] -= b_unscale * gathered[i];
  }
  for (int s = f.num_supernodes - 1; s >= 0; --s) {  // L^T w = z: w_D = T^T z_D - W^T w_B
    const int k0 = f.super[s], nc = f.super[s + 1] - k0, nr = f.pi[s + 1] - f.pi[s];
    const std::uint16_t* l = f.values + f.px[s];
    prefetch.StartBackward(f.px[s + 1]);
    float* ys = y + k0;
    const int* rows = f.rows + f.pi[s];
    for (int i = 0; i < nc; ++i) gathered[i] = t_unscale * ys[i];
    for (int i = nc; i < nr; ++i) gathered[i] = -b_unscale * y[rows[i]];
    ForColumnGroups(nc, [&]<int C>(int j) {
      float dots[C];
      DotGroup<C>(l, nr, j, gathered, dots, prefetch);
      for (int c = 0; c < C; ++c) ys[j + c] = dots[c];
    });
  }
}

void ConvertToHalfF16c(const double* x, std::size_t n, double scale, std::uint16_t* out) {
  std::size_t k = 0;
  const __m256d s = _mm256_set1_pd(scale);
  for (; k + 8 <= n; k += 8) {
    const __m128 lo = _mm256_cvtpd_ps(_mm256_mul_pd(s, _mm256_loadu_pd(x + k)));
    const __m128 hi = _mm256_cvtpd_ps(_mm256_mul_pd(s, _mm256_loadu_pd(x + k + 4)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + k),
                     _mm256_cvtps_ph(_mm256_set_m128(hi, lo), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
  }
  for (; k < n; ++k)
    out[k] = _cvtss_sh(static_cast<float>(scale * x[k]), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
}

}  // namespace vesica::physics

#pragma GCC pop_options
