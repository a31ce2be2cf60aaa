#pragma once
// Internal to cholmod_solver.cpp: a supernodal Cholesky factor stored as its partitioned inverse in
// IEEE half (binary16) times power-of-two scales, solved in float. The preconditioner solve of kRotatedFactorPcg
// streams the whole factor twice; half the bytes of the float copy. Needs F16C (with AVX2 and
// FMA), compiled for it in half_factor_f16c.cpp and chosen at run time.

#include <cstddef>
#include <cstdint>

namespace vesica::physics {

/// Supernode s holds columns [super[s], super[s+1]) of pi[s+1] - pi[s] = nr rows (row indices
/// rows[pi[s]...], the first nc ones its own columns). With L_D its nc x nc lower triangle and L_B
/// the nr - nc rows below, it is stored as the partitioned inverse [T; W] = [L_D; L_B] L_D^-1
/// (T = L_D^-1, W = L_B L_D^-1), T and W each times a power of two of the supernode's own that
/// brings its largest entry near 2^14 (binary16 tops out at 65504). Then the solves are
/// products with no chain of dependent steps inside a supernode: forward z_D = T y_D and
/// y_B -= W y_D; backward w_D = T^T z_D - W^T w_B. From values[px[s]], in tiles: the columns in
/// groups (HalfFactorGroupWidth), each group's rows from its first column's diagonal down in chunks
/// of 8, a chunk's C columns of 8 rows one after the other (zeros above the diagonal and past nr).
/// One contiguous stream a solve; CHOLMOD's layout would also store the zero upper triangle of each
/// diagonal block (a fifth of the entries of a 3D grid's factor; the tiles' zeros add ~2.5 %).
struct HalfFactorView {
  const int* super = nullptr;
  const int* pi = nullptr;
  const std::size_t* px = nullptr;
  const int* rows = nullptr;
  int num_supernodes = 0;
  const std::uint16_t* values = nullptr;
  /// Supernode s's T is stored times 1 / unscales[2 s], its W times 1 / unscales[2 s + 1].
  const float* unscales = nullptr;
};

/// Floats past a supernode's rows that the kernels read and write in `gathered` (one vector).
constexpr int kHalfFactorPadding = 8;

/// Width of the column group that starts at column j of a supernode of nc columns: 8 while 8 are
/// left, then 4, then the last 1-3 together.
inline int HalfFactorGroupWidth(int nc, int j) { return nc - j >= 8 ? 8 : nc - j >= 4 ? 4 : nc - j; }

/// Entries of a supernode of nr rows and nc columns in the tiled layout.
inline std::size_t TiledSupernodeEntries(int rows, int columns) {
  std::size_t entries = 0;
  for (int j = 0, width = 0; j < columns; j += width) {
    width = HalfFactorGroupWidth(columns, j);
    entries += static_cast<std::size_t>(width) * 8 * ((rows - j + 7) / 8);
  }
  return entries;
}

/// True when this CPU runs the F16C kernels.
bool HalfFactorSupported();
/// Writes a supernode's [T; W] (nr x nc, column-major in `block`) in the tiled layout, T's rows times
/// triangle_scale and W's times below_scale (TiledSupernodeEntries(nr, nc) entries). Only when
/// HalfFactorSupported().
void WriteTiledSupernodeF16c(const float* block, int nr, int nc, double triangle_scale, double below_scale,
                             std::uint16_t* out);
/// y <- (L L^T)^-1 y in the factor's permuted order; `gathered` holds the widest supernode's row
/// count plus kHalfFactorPadding floats. Only when HalfFactorSupported().
void HalfFactorSolveF16c(const HalfFactorView& factor, float* y, float* gathered);

}  // namespace vesica::physics
