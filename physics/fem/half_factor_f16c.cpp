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

// No software prefetch: the tiles are one stream a supernode, which the hardware prefetchers
// follow; the 64 KB cursor that helped the column-major layout's interleaved column streams
// (docs/performance/fem.md, round 9) made the tiled solve 3-5 % slower.

// y[0..8 chunks) += sum_c a[c] L_c over the tiles of a group of C columns (half_factor.h), y read
// and written once for the C columns; returns the next group's tiles.
template <int C>
inline const std::uint16_t* AxpyTiles(const float* a, const std::uint16_t* tile, int chunks, float* y) {
  vf coefficient[C];
  for (int c = 0; c < C; ++c) coefficient[c] = Splat(a[c]);
  for (int k = 0; k < chunks; ++k, tile += C * W) {
    vf v = Load(y + W * k);
    for (int c = 0; c < C; ++c) v = Fma(coefficient[c], LoadHalf(tile + W * c), v);
    Store(y + W * k, v);
  }
  return tile;
}

// out[c] = L_c . y[0..8 chunks) over the tiles of a group of C columns, y read once; returns the
// next group's tiles.
template <int C>
inline const std::uint16_t* DotTiles(const std::uint16_t* tile, int chunks, const float* y, float* out) {
  vf sum[C];
  for (int c = 0; c < C; ++c) sum[c] = Zero();
  for (int k = 0; k < chunks; ++k, tile += C * W) {
    const vf v = Load(y + W * k);
    for (int c = 0; c < C; ++c) sum[c] = Fma(LoadHalf(tile + W * c), v, sum[c]);
  }
  for (int c = 0; c < C; ++c) out[c] = Sum(sum[c]);
  return tile;
}

// group.template operator()<C>(j) for the column groups [j, j + C) of a supernode of nc columns
// (HalfFactorGroupWidth, which the tiles' writer follows too).
template <typename Group>
inline void ForColumnGroups(int nc, Group&& group) {
  for (int j = 0, width = 0; j < nc; j += width) {
    width = HalfFactorGroupWidth(nc, j);
    switch (width) {
      case 8:
        group.template operator()<8>(j);
        break;
      case 4:
        group.template operator()<4>(j);
        break;
      case 3:
        group.template operator()<3>(j);
        break;
      case 2:
        group.template operator()<2>(j);
        break;
      default:
        group.template operator()<1>(j);
        break;
    }
  }
}

}  // namespace

void HalfFactorSolveF16c(const HalfFactorView& f, float* y, float* gathered) {
  for (int s = 0; s < f.num_supernodes; ++s) {  // L z = y: z_D = T y_D, y_B -= W y_D
    const int k0 = f.super[s], nc = f.super[s + 1] - k0, nr = f.pi[s + 1] - f.pi[s];
    // Copies: y's stores could alias the view's floats, and the loops would re-read them.
    const float t_unscale = f.unscales[2 * s], b_unscale = f.unscales[2 * s + 1];
    const std::uint16_t* tile = f.values + f.px[s];
    float* ys = y + k0;
    for (int i = 0; i < nr; ++i) gathered[i] = 0.0f;
    ForColumnGroups(nc, [&]<int C>(int j) { tile = AxpyTiles<C>(ys + j, tile, (nr - j + W - 1) / W, gathered + j); });
    for (int i = 0; i < nc; ++i) ys[i] = t_unscale * gathered[i];
    const int* rows = f.rows + f.pi[s];
    for (int i = nc; i < nr; ++i) y[rows[i]] -= b_unscale * gathered[i];
  }
  for (int s = f.num_supernodes - 1; s >= 0; --s) {  // L^T w = z: w_D = T^T z_D - W^T w_B
    const int k0 = f.super[s], nc = f.super[s + 1] - k0, nr = f.pi[s + 1] - f.pi[s];
    const float t_unscale = f.unscales[2 * s], b_unscale = f.unscales[2 * s + 1];
    const std::uint16_t* tile = f.values + f.px[s];
    float* ys = y + k0;
    const int* rows = f.rows + f.pi[s];
    for (int i = 0; i < nc; ++i) gathered[i] = t_unscale * ys[i];
    for (int i = nc; i < nr; ++i) gathered[i] = -b_unscale * y[rows[i]];
    // The tiles' zero rows past nr meet these: zeros, not what an earlier solve (maybe of a
    // non-finite y) left there, since 0 x NaN is NaN.
    for (int i = nr; i < nr + W; ++i) gathered[i] = 0.0f;
    ForColumnGroups(nc, [&]<int C>(int j) {
      float dots[C];
      tile = DotTiles<C>(tile, (nr - j + W - 1) / W, gathered + j, dots);
      for (int c = 0; c < C; ++c) ys[j + c] = dots[c];
    });
  }
}

void WriteTiledSupernodeF16c(const float* block, int nr, int nc, double triangle_scale, double below_scale,
                             std::uint16_t* out) {
  for (int j = 0, width = 0; j < nc; j += width) {
    width = HalfFactorGroupWidth(nc, j);
    for (int k0 = j; k0 < nr; k0 += W)
      for (int c = j; c < j + width; ++c, out += W) {
        alignas(32) float chunk[W];
        for (int r = 0; r < W; ++r) {
          const int row = k0 + r;
          const double scale = row < nc ? triangle_scale : below_scale;
          chunk[r] = row >= c && row < nr ? static_cast<float>(scale * block[static_cast<std::ptrdiff_t>(c) * nr + row])
                                          : 0.0f;
        }
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out),
                         _mm256_cvtps_ph(_mm256_load_ps(chunk), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
      }
  }
}

}  // namespace vesica::physics

#pragma GCC pop_options
