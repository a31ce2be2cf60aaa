#pragma once
// Internal to pcg_solver.cpp and elastic_forces.cpp: the 3x3-block row kernels of the system
// matrix (symmetric product, block Gauss-Seidel sweeps) with AVX2 + FMA, compiled for it in
// block_rows_avx2.cpp and chosen at run time (the project builds without -march, so the portable
// loops get SSE2 and no FMA). One block row is a 4-wide masked load of each of its 3 columns'
// triplets against the 3 entries of x (instead of 9 scalar multiply-adds). Same sums as the
// scalar loops up to rounding (FMA, other association).

namespace vesica::physics {

/// A symmetric pattern matrix (SparsePattern + values) by raw pointers; row i of node blocks is
/// column i (read as rows, gather form).
struct BlockRowsView {
  int nodes = 0;
  const int* outer = nullptr;          ///< structure.outerIndexPtr(), per dof column
  const int* inner = nullptr;          ///< structure.innerIndexPtr()
  const int* column_stride = nullptr;  ///< per node
  const int* diagonal_slot = nullptr;  ///< per dof
  const double* values = nullptr;
};

/// True when this CPU runs the AVX2 + FMA kernels and VESICA_FEM_ELEMENT_KERNEL does not ask for
/// scalar (the same switch as the element pass, so one variable forces every FEM kernel scalar).
bool BlockRowKernelsUseAvx2();

/// y = A x (3 nodes doubles each).
void SymmetricPatternMultiplyAvx2(const BlockRowsView& a, const double* x, double* y);
/// Doubles of scratch the sweeps need: x (and y) padded to 4 a node, 32-byte aligned inside.
inline int BlockRowSweepScratch(int nodes) { return 2 * (4 * nodes + 4); }
/// One block Gauss-Seidel sweep, as BlockGaussSeidelSweep; inverse_diagonal: 9 doubles a node,
/// column-major (std::vector<Eigen::Matrix3d>'s storage).
void BlockGaussSeidelSweepAvx2(const BlockRowsView& a, const double* inverse_diagonal, const double* b, double* x,
                               bool forward, double* scratch);
/// As ForwardSweepFromZeroAndUpperTimes (x = (D + L)^-1 b, y = U x; both written).
void ForwardSweepFromZeroAndUpperTimesAvx2(const BlockRowsView& a, const double* inverse_diagonal, const double* b,
                                           double* x, double* y, double* scratch);

/// The node blocks of a symmetric matrix as rows of floats (block sparse row): node i's blocks
/// (i, j) for blocks [row_begin[i], row_begin[i+1]), j = column[block] ascending, 9 floats each,
/// A(3i+r, 3j+c) at 9 block + 3r + c; values padded by 4 floats (the kernels read 4 at a time).
struct FloatBlockRowsView {
  int nodes = 0;
  const int* row_begin = nullptr;       ///< nodes + 1
  const int* diagonal_block = nullptr;  ///< per node: its block (i, i)
  const int* column = nullptr;          ///< per block
  const float* values = nullptr;
};

/// The sweeps above on the float rows (arithmetic in double).
void FloatBlockGaussSeidelSweepAvx2(const FloatBlockRowsView& a, const double* inverse_diagonal, const double* b,
                                    double* x, bool forward, double* scratch);
void FloatForwardSweepFromZeroAndUpperTimesAvx2(const FloatBlockRowsView& a, const double* inverse_diagonal,
                                                const double* b, double* x, double* y, double* scratch);

}  // namespace vesica::physics
