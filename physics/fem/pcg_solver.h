#pragma once
// Preconditioned conjugate gradient on a symmetric pattern matrix (gallbladder paper §2.2: tolerance
// 1e-8, at most 20 iterations, warm started from the previous solution).

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "physics/fem/cg_spectrum_estimate.h"
#include "physics/fem/huge_page_allocator.h"
#include "physics/fem/sparse_pattern.h"

namespace vesica::physics {

struct PcgResult {
  int iterations = 0;
  double relative_residual = 0.0;  ///< |b - A x| / |b| at exit (0 when b = 0)
  bool converged = false;
  /// The solve could not go on: |b| not finite (overflowing or NaN), or p.A p < 0 or NaN along a
  /// search direction (A or the preconditioner not positive definite, or the iterates overflowed).
  /// x is then not a solution to accept, however many iterations the caller allows.
  bool breakdown = false;
  /// Extreme eigenvalues of P^-1 A from this solve's first kPcgSpectrumIterations iterations
  /// ({0, 0} without an iteration): how well the preconditioner fits, and so the iteration count.
  SpectrumEstimate spectrum;
};

/// Iterations whose coefficients PcgResult::spectrum is estimated from (the extremes converge
/// first; a longer solve's later iterations would only sharpen them).
inline constexpr int kPcgSpectrumIterations = 64;

/// z = P^-1 r.
using Preconditioner = std::function<void(const Eigen::VectorXd& r, Eigen::VectorXd& z)>;

class FloatBlockRows;

/// Inverse 3x3 diagonal blocks of a pattern matrix, applied as a preconditioner.
class BlockJacobiPreconditioner {
 public:
  void Compute(const SparsePattern& pattern, const Eigen::VectorXd& values);
  /// From the float rows' diagonal blocks (inverted in double).
  void Compute(const FloatBlockRows& rows);
  void Apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  const std::vector<Eigen::Matrix3d>& inverse_blocks() const { return inverse_blocks_; }

 private:
  std::vector<Eigen::Matrix3d> inverse_blocks_;
};

/// One block Gauss-Seidel sweep on A x = b (3x3 node blocks, inverse diagonal blocks given),
/// updating x in place: x + (D + L)^-1 (b - A x) in node order (forward) or x + (D + U)^-1 (b - A x)
/// in reverse order. A forward sweep, a correction and a backward sweep make a symmetric
/// multiplicative preconditioner, positive definite for any SPD correction.
void BlockGaussSeidelSweep(const SparsePattern& pattern, const Eigen::VectorXd& values,
                           const std::vector<Eigen::Matrix3d>& inverse_diagonal, const Eigen::VectorXd& b,
                           Eigen::VectorXd& x, bool forward);

/// y = U x with U the blocks of A right of the diagonal (row node i, column node j > i). After a
/// forward sweep from x = 0, b - A x = -U x: half the reads of a full product.
void UpperBlocksTimes(const SparsePattern& pattern, const Eigen::VectorXd& values, const Eigen::VectorXd& x,
                      Eigen::VectorXd& y);

/// The forward sweep from x = 0 and y = U x in one pass over the blocks left of the diagonal:
/// x = (D + L)^-1 b, then b - A x = -y. Row i's blocks left of the diagonal are, by symmetry,
/// column i's blocks above it, so right after x_i is known they scatter U's contributions
/// y_j += A_ji x_i (j < i) from cache. Reads half the matrix; a sweep from zero plus
/// UpperBlocksTimes read one and a half.
void ForwardSweepFromZeroAndUpperTimes(const SparsePattern& pattern, const Eigen::VectorXd& values,
                                       const std::vector<Eigen::Matrix3d>& inverse_diagonal, const Eigen::VectorXd& b,
                                       Eigen::VectorXd& x, Eigen::VectorXd& y);

/// A symmetric pattern matrix rounded to float, in node-block rows (9 floats a block, one column
/// index a block), for the Gauss-Seidel sweeps of a preconditioner: a third of the bytes the
/// double sweeps stream (values and row indices), and a preconditioner needs no more digits.
/// Needs AVX2 + FMA (block_rows_simd.h); available() is false without them (or with
/// VESICA_FEM_ELEMENT_KERNEL=scalar), and callers then sweep the double matrix.
class FloatBlockRows {
 public:
  /// Builds the block structure (first use or another pattern) and rounds the values.
  void Update(const SparsePattern& pattern, const Eigen::VectorXd& values);
  /// Builds the block structure for `pattern` unless it has it already; values keep theirs, zero
  /// when new. For writers of values() that do not go through Update.
  void Reshape(const SparsePattern& pattern);
  /// Per pattern value index (slot), where that entry lives in values(): the map a writer of
  /// the rows needs (entry (row 3j + c, column 3i + r) is 9 k + 3 r + c of block k = (i, j)).
  std::vector<int> ValueIndexOfSlots(const SparsePattern& pattern) const;
  float* values() { return values_.data(); }
  /// Appends row `dof` (its column indices and values, as doubles), LocalBlockCorrection's row source.
  void AppendRow(int dof, std::vector<int>& columns, std::vector<double>& values) const;
  static bool available();
  int nodes() const { return nodes_; }

 private:
  friend void BlockGaussSeidelSweep(const FloatBlockRows&, const std::vector<Eigen::Matrix3d>&, const Eigen::VectorXd&,
                                    Eigen::VectorXd&, bool);
  friend void ForwardSweepFromZeroAndUpperTimes(const FloatBlockRows&, const std::vector<Eigen::Matrix3d>&,
                                                const Eigen::VectorXd&, Eigen::VectorXd&, Eigen::VectorXd&);
  friend class BlockJacobiPreconditioner;
  int nodes_ = 0;
  long nonzeros_ = -1;  // of the pattern the structure was built for
  std::vector<int> row_begin_, diagonal_block_;
  HugePageVector<int> column_;
  std::vector<int> source_;         // per block (i, j): value index of entry (3j, 3i) in the pattern
  std::vector<int> source_stride_;  // per block: the column stride of node i
  HugePageVector<float> values_;
};

/// BlockGaussSeidelSweep and ForwardSweepFromZeroAndUpperTimes on the float rows (only when
/// FloatBlockRows::available()).
void BlockGaussSeidelSweep(const FloatBlockRows& rows, const std::vector<Eigen::Matrix3d>& inverse_diagonal,
                           const Eigen::VectorXd& b, Eigen::VectorXd& x, bool forward);
void ForwardSweepFromZeroAndUpperTimes(const FloatBlockRows& rows, const std::vector<Eigen::Matrix3d>& inverse_diagonal,
                                       const Eigen::VectorXd& b, Eigen::VectorXd& x, Eigen::VectorXd& y);

/// y = A x.
using MatrixOperator = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)>;

/// Solves A x = b with A given as products (matrix-free); x holds the warm start on entry.
/// initial_product: A x for that warm start when the caller has it (saves one product), or null.
/// final_product (optional): A x at exit, as b - r with r the updated residual (equal to the true
/// product up to rounding, |error| <~ 1e-15 |b| per iteration), so a caller needs no product of
/// its own.
PcgResult SolvePcg(const MatrixOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                   const Preconditioner& preconditioner, double relative_tolerance, int max_iterations,
                   const Eigen::VectorXd* initial_product = nullptr, Eigen::VectorXd* final_product = nullptr);

/// Solves A x = b; x holds the warm start on entry and the solution on exit.
PcgResult SolvePcg(const SparsePattern& pattern, const Eigen::VectorXd& values,
                   const Eigen::VectorXd& b, Eigen::VectorXd& x, const Preconditioner& preconditioner,
                   double relative_tolerance, int max_iterations);

}  // namespace vesica::physics
