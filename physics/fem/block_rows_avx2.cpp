// Block-row kernels of the system matrix with AVX2 + FMA (block_rows_simd.h). Headers come before
// the target region so none of their inline functions is compiled for AVX2.

#include <immintrin.h>

#include <cstdint>

#include "physics/fem/block_rows_simd.h"
#include "physics/fem/elastic_forces.h"

#pragma GCC push_options
#pragma GCC target("avx2,fma")

namespace vesica::physics {
namespace {

inline __m256i Three() { return _mm256_set_epi64x(0, -1, -1, -1); }

// Adds the products of the blocks in slots [begin, end) of row i (3 columns `stride` apart) with
// x to the three accumulators (lane 3 stays 0). X(dof) loads x's 3 entries from dof on, lane 3 0.
template <typename LoadX>
inline void GatherBlocks(const double* v, const int* inner, const LoadX& load_x, int begin, int end, int stride,
                         __m256d& s0, __m256d& s1, __m256d& s2) {
  const __m256i three = Three();
  for (int k = begin; k < end; k += 3) {
    const __m256d xa = load_x(inner[k]);
    const double* c0 = v + k;
    s0 = _mm256_fmadd_pd(_mm256_maskload_pd(c0, three), xa, s0);
    s1 = _mm256_fmadd_pd(_mm256_maskload_pd(c0 + stride, three), xa, s1);
    s2 = _mm256_fmadd_pd(_mm256_maskload_pd(c0 + 2 * stride, three), xa, s2);
  }
}

// x copied to 4 doubles a node (lane 3 zero), 32-byte aligned: the sweeps write x_i as one
// vector and read it back a row or two later, which a 3-lane masked store would not forward.
class PaddedNodes {
 public:
  // storage: at least 4 * nodes + 4 doubles (kBlockRowScratchPerNode), zeroed here.
  PaddedNodes(double* storage, int nodes) {
    const auto address = reinterpret_cast<std::uintptr_t>(storage);
    data_ = storage + ((32 - address % 32) % 32) / sizeof(double);
    for (int k = 0; k < 4 * nodes; ++k) data_[k] = 0.0;
  }
  void CopyFrom(const double* x, int nodes) {
    for (int i = 0; i < nodes; ++i) data_[4 * i] = x[3 * i], data_[4 * i + 1] = x[3 * i + 1], data_[4 * i + 2] = x[3 * i + 2];
  }
  void CopyTo(double* x, int nodes) const {
    for (int i = 0; i < nodes; ++i) x[3 * i] = data_[4 * i], x[3 * i + 1] = data_[4 * i + 1], x[3 * i + 2] = data_[4 * i + 2];
  }
  // Node of x's entry `dof` (a multiple of 3).
  __m256d Load(int dof) const { return _mm256_load_pd(data_ + dof + dof / 3); }
  void Store(int node, __m256d v) { _mm256_store_pd(data_ + 4 * node, v); }
  double* data() { return data_; }

 private:
  double* data_;
};

// (sum of s0's lanes, of s1's, of s2's, 0).
inline __m256d Sums(__m256d s0, __m256d s1, __m256d s2) {
  const __m256d h01 = _mm256_hadd_pd(s0, s1);                     // s0[0]+s0[1], s1[0]+s1[1], s0[2]+s0[3], s1[2]+s1[3]
  const __m256d h2 = _mm256_hadd_pd(s2, _mm256_setzero_pd());     // s2[0]+s2[1], 0, s2[2]+s2[3], 0
  const __m256d lo = _mm256_permute2f128_pd(h01, h2, 0x20);      // h01 low, h2 low
  const __m256d hi = _mm256_permute2f128_pd(h01, h2, 0x31);      // h01 high, h2 high
  return _mm256_add_pd(lo, hi);
}

// inverse (column-major 3x3) * t, lane 3 = 0.
inline __m256d Times(const double* inverse, __m256d t) {
  const __m256i three = Three();
  __m256d out = _mm256_mul_pd(_mm256_maskload_pd(inverse, three), _mm256_permute4x64_pd(t, 0x00));
  out = _mm256_fmadd_pd(_mm256_maskload_pd(inverse + 3, three), _mm256_permute4x64_pd(t, 0x55), out);
  return _mm256_fmadd_pd(_mm256_maskload_pd(inverse + 6, three), _mm256_permute4x64_pd(t, 0xaa), out);
}

}  // namespace

bool BlockRowKernelsUseAvx2() {
  static const bool use = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
           ResolveElementKernel(ElementKernel::kAuto) != ElementKernel::kScalar;
  }();
  return use;
}

void SymmetricPatternMultiplyAvx2(const BlockRowsView& a, const double* x, double* y) {
  const __m256i three = Three();
  const auto load_x = [&](int dof) { return _mm256_maskload_pd(x + dof, three); };
  for (int i = 0; i < a.nodes; ++i) {
    const int begin = a.outer[3 * i], stride = a.column_stride[i];
    __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0;
    GatherBlocks(a.values, a.inner, load_x, begin, begin + stride, stride, s0, s1, s2);
    _mm256_maskstore_pd(y + 3 * i, three, Sums(s0, s1, s2));
  }
}

void BlockGaussSeidelSweepAvx2(const BlockRowsView& a, const double* inverse_diagonal, const double* b, double* x,
                               bool forward, double* scratch) {
  const __m256i three = Three();
  PaddedNodes padded(scratch, a.nodes);
  padded.CopyFrom(x, a.nodes);
  const auto load_x = [&](int dof) { return padded.Load(dof); };
  for (int step = 0; step < a.nodes; ++step) {
    const int i = forward ? step : a.nodes - 1 - step;
    const int begin = a.outer[3 * i], stride = a.column_stride[i];
    const int diagonal = a.diagonal_slot[3 * i];  // rows are sorted: blocks before it are j < i
    __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0;
    GatherBlocks(a.values, a.inner, load_x, begin, diagonal, stride, s0, s1, s2);
    GatherBlocks(a.values, a.inner, load_x, diagonal + 3, begin + stride, stride, s0, s1, s2);
    const __m256d t = _mm256_sub_pd(_mm256_maskload_pd(b + 3 * i, three), Sums(s0, s1, s2));
    padded.Store(i, Times(inverse_diagonal + 9 * i, t));
  }
  padded.CopyTo(x, a.nodes);
}

void ForwardSweepFromZeroAndUpperTimesAvx2(const BlockRowsView& a, const double* inverse_diagonal, const double* b,
                                           double* x, double* y, double* scratch) {
  const __m256i three = Three();
  PaddedNodes padded_x(scratch, a.nodes), padded_y(scratch + 4 * a.nodes + 4, a.nodes);  // zeros
  const auto load_x = [&](int dof) { return padded_x.Load(dof); };
  double* ys = padded_y.data();
  for (int i = 0; i < a.nodes; ++i) {
    const int begin = a.outer[3 * i], stride = a.column_stride[i];
    const int diagonal = a.diagonal_slot[3 * i];  // blocks before it: rows of nodes j < i
    __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0;
    GatherBlocks(a.values, a.inner, load_x, begin, diagonal, stride, s0, s1, s2);  // x_j = 0 for j > i
    const __m256d t = _mm256_sub_pd(_mm256_maskload_pd(b + 3 * i, three), Sums(s0, s1, s2));
    const __m256d xi = Times(inverse_diagonal + 9 * i, t);
    padded_x.Store(i, xi);
    const __m256d x0 = _mm256_permute4x64_pd(xi, 0x00), x1 = _mm256_permute4x64_pd(xi, 0x55),
                  x2 = _mm256_permute4x64_pd(xi, 0xaa);
    for (int k = begin; k < diagonal; k += 3) {  // y_j += A_ji x_i, rows 3j..3j+2 of column block i
      double* yj = ys + a.inner[k] + a.inner[k] / 3;
      const double* c0 = a.values + k;
      __m256d acc = _mm256_fmadd_pd(_mm256_maskload_pd(c0, three), x0, _mm256_load_pd(yj));
      acc = _mm256_fmadd_pd(_mm256_maskload_pd(c0 + stride, three), x1, acc);
      _mm256_store_pd(yj, _mm256_fmadd_pd(_mm256_maskload_pd(c0 + 2 * stride, three), x2, acc));
    }
  }
  padded_x.CopyTo(x, a.nodes);
  padded_y.CopyTo(y, a.nodes);
}

namespace {

// As GatherBlocks, for blocks [begin, end) of the float rows: row r of a block widened to double
// (its 4th float is the next row's first: times x's lane 3, which is 0).
inline void GatherFloatBlocks(const FloatBlockRowsView& a, const double* x4, int begin, int end, __m256d& s0,
                              __m256d& s1, __m256d& s2) {
  for (int k = begin; k < end; ++k) {
    const __m256d xa = _mm256_load_pd(x4 + 4 * a.column[k]);
    const float* rows = a.values + 9 * static_cast<long>(k);
    s0 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(rows)), xa, s0);
    s1 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(rows + 3)), xa, s1);
    s2 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(rows + 6)), xa, s2);
  }
}

}  // namespace

void FloatBlockGaussSeidelSweepAvx2(const FloatBlockRowsView& a, const double* inverse_diagonal, const double* b,
                                    double* x, bool forward, double* scratch) {
  const __m256i three = Three();
  PaddedNodes padded(scratch, a.nodes);
  padded.CopyFrom(x, a.nodes);
  const double* x4 = padded.data();
  for (int step = 0; step < a.nodes; ++step) {
    const int i = forward ? step : a.nodes - 1 - step;
    __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0;
    GatherFloatBlocks(a, x4, a.row_begin[i], a.diagonal_block[i], s0, s1, s2);
    GatherFloatBlocks(a, x4, a.diagonal_block[i] + 1, a.row_begin[i + 1], s0, s1, s2);
    const __m256d t = _mm256_sub_pd(_mm256_maskload_pd(b + 3 * i, three), Sums(s0, s1, s2));
    padded.Store(i, Times(inverse_diagonal + 9 * i, t));
  }
  padded.CopyTo(x, a.nodes);
}

void FloatForwardSweepFromZeroAndUpperTimesAvx2(const FloatBlockRowsView& a, const double* inverse_diagonal,
                                                const double* b, double* x, double* y, double* scratch) {
  const __m256i three = Three();
  PaddedNodes padded_x(scratch, a.nodes), padded_y(scratch + 4 * a.nodes + 4, a.nodes);  // zeros
  const double* x4 = padded_x.data();
  double* y4 = padded_y.data();
  for (int i = 0; i < a.nodes; ++i) {
    __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0;
    GatherFloatBlocks(a, x4, a.row_begin[i], a.diagonal_block[i], s0, s1, s2);  // x_j = 0 for j > i
    const __m256d t = _mm256_sub_pd(_mm256_maskload_pd(b + 3 * i, three), Sums(s0, s1, s2));
    const __m256d xi = Times(inverse_diagonal + 9 * i, t);
    padded_x.Store(i, xi);
    const __m256d x0 = _mm256_permute4x64_pd(xi, 0x00), x1 = _mm256_permute4x64_pd(xi, 0x55),
                  x2 = _mm256_permute4x64_pd(xi, 0xaa);
    // y_j += A_ji x_i = sum_r x_i[r] (row r of block (i, j)); lane 3 collects junk CopyTo drops.
    for (int k = a.row_begin[i]; k < a.diagonal_block[i]; ++k) {
      double* yj = y4 + 4 * a.column[k];
      const float* rows = a.values + 9 * static_cast<long>(k);
      __m256d acc = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(rows)), x0, _mm256_load_pd(yj));
      acc = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(rows + 3)), x1, acc);
      _mm256_store_pd(yj, _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(rows + 6)), x2, acc));
    }
  }
  padded_x.CopyTo(x, a.nodes);
  padded_y.CopyTo(y, a.nodes);
}

}  // namespace vesica::physics

#pragma GCC pop_options
