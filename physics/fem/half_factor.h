#pragma once
// Internal to cholmod_solver.cpp: a supernodal Cholesky factor stored as IEEE half (binary16)
// times a power-of-two scale, solved in float. The preconditioner solve of kRotatedFactorPcg
// streams the whole factor twice; half the bytes of the float copy. Needs F16C (with AVX2 and
// FMA), compiled for it in half_factor_f16c.cpp and chosen at run time.

#include <cstddef>
#include <cstdint>

namespace vesica::physics {

/// Supernode s holds columns [super[s], super[s+1]) of pi[s+1] - pi[s] = nr rows (row indices
/// rows[pi[s]...], the first ones its own columns), column-major from values[px[s]] like CHOLMOD's
/// supernodal factor, but packed: its column j stores rows j..nr-1 only, from
/// values[px[s] + j nr - j (j - 1) / 2]. CHOLMOD's layout also stores the zero upper triangle of each
/// diagonal block (a fifth of the entries of a 3D grid's factor), and the solve streams the factor.
struct HalfFactorView {
  const int* super = nullptr;
  const int* pi = nullptr;
  const std::size_t* px = nullptr;
  const int* rows = nullptr;
  int num_supernodes = 0;
  const std::uint16_t* values = nullptr;  ///< followed by kHalfFactorPadding readable entries
  /// For the k-th 4-column panel of supernode s (k < ceil(nc / 4), panel first_panel[s] + k; the
  /// last one has nc % 4 columns when that is not 0): the inverse M of its lower triangle in float,
  /// by columns, zero-padded to 4 x 4, then M^T by columns (kPanelInverseFloats floats). The
  /// triangle is solved as one small product, not a chain of dependent divisions; the same M in
  /// both solves keeps the preconditioner symmetric.
  const float* panel_inverses = nullptr;
  const int* first_panel = nullptr;
};

constexpr int kPanelInverseFloats = 32;

/// Entries past the last the kernels may read (one vector of halves).
constexpr int kHalfFactorPadding = 8;

/// Entries of a supernode of nr rows and nc columns in the packed layout: nr nc - nc (nc - 1) / 2.
inline std::size_t PackedSupernodeEntries(int rows, int columns) {
  return static_cast<std::size_t>(rows) * columns - static_cast<std::size_t>(columns) * (columns - 1) / 2;
}

/// True when this CPU runs the F16C kernels.
bool HalfFactorSupported();
/// out[k] = half(scale * x[k]); call only when HalfFactorSupported().
void ConvertToHalfF16c(const double* x, std::size_t n, double scale, std::uint16_t* out);
/// y <- (L L^T)^-1 y in the factor's permuted order, L the stored (scaled) factor; `gathered`
/// holds at least the widest supernode's below-diagonal row count. Only when HalfFactorSupported().
void HalfFactorSolveF16c(const HalfFactorView& factor, float* y, float* gathered);

}  // namespace vesica::physics
