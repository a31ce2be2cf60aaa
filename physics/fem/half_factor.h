#pragma once
// Internal to cholmod_solver.cpp: a supernodal Cholesky factor stored as IEEE half (binary16)
// times a power-of-two scale, solved in float. The preconditioner solve of kRotatedFactorPcg
// streams the whole factor twice; half the bytes of the float copy. Needs F16C (with AVX2 and
// FMA), compiled for it in half_factor_f16c.cpp and chosen at run time.

#include <cstddef>
#include <cstdint>

namespace vesica::physics {

/// Supernode s holds columns [super[s], super[s+1]) of pi[s+1] - pi[s] = nr rows (row indices
/// rows[pi[s]...], the first nc ones its own columns). With L_D its nc x nc lower triangle and L_B
/// the nr - nc rows below, it is stored as the partitioned inverse [T; W] = [L_D; L_B] L_D^-1
/// (T = L_D^-1, W = L_B L_D^-1), T times triangle_scale and W times below_scale (powers of two that
/// keep each part's largest entry near 2^14: binary16 tops out at 65504). Then the solves are
/// products with no chain of dependent steps inside a supernode: forward z_D = T y_D and
/// y_B -= W y_D; backward w_D = T^T z_D - W^T w_B. Column-major like CHOLMOD's supernodal factor
/// but packed: column j stores rows j..nr-1 only (T is lower triangular), from
/// values[px[s] + j nr - j (j - 1) / 2]. CHOLMOD's layout also stores the zero upper triangle of
/// each diagonal block (a fifth of the entries of a 3D grid's factor), and the solve streams the factor.
struct HalfFactorView {
  const int* super = nullptr;
  const int* pi = nullptr;
  const std::size_t* px = nullptr;
  const int* rows = nullptr;
  int num_supernodes = 0;
  const std::uint16_t* values = nullptr;  ///< followed by kHalfFactorPadding readable entries
  float triangle_unscale = 1.0f;          ///< 1 / triangle_scale
  float below_unscale = 1.0f;             ///< 1 / below_scale
};

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
/// y <- (L L^T)^-1 y in the factor's permuted order; `gathered` holds the widest supernode's row
/// count plus one vector (kHalfFactorPadding) of floats, all finite. Only when HalfFactorSupported().
void HalfFactorSolveF16c(const HalfFactorView& factor, float* y, float* gathered);

}  // namespace vesica::physics
