#pragma once
// Sparse Cholesky of a symmetric positive definite pattern matrix through SuiteSparse CHOLMOD.
// The symbolic analysis is done once per pattern; numeric factorisations reuse it.

#include <Eigen/Core>
#include <future>
#include <memory>
#include <vector>

#include "physics/fem/sparse_pattern.h"

namespace vesica::physics {

class CholmodSolver {
 public:
  CholmodSolver();
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Factorises A (values in pattern order). Returns false when A is not positive definite.
  /// keep_single_precision: also keep L rounded to float for SolveSinglePrecision; with
  /// half_storage on a CPU with F16C, rounded to IEEE half instead (times a power of two; relative
  /// error ~5e-4, a quarter of the double factor's bytes), still solved in float.
  bool Factorize(const SparsePattern& pattern, const Eigen::VectorXd& values, bool keep_single_precision = false,
                 bool half_storage = false);
  bool factorized() const;
  /// The low-precision copy is the half one (half_storage was asked for and the CPU has F16C).
  bool half_storage() const;
  /// Bytes of factor values a low-precision solve reads each way (0 without the copy): what it
  /// streams through the caches twice a solve.
  std::size_t low_precision_bytes() const;
  /// x = A^-1 b with the last successful factorisation. The solves may be called from several
  /// threads at once (not during Factorize).
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// X = A^-1 B for several right-hand sides (3 columns: a node's unit forces) in one pass over the
  /// factor.
  void Solve(const Eigen::Matrix<double, Eigen::Dynamic, 3>& b, Eigen::Matrix<double, Eigen::Dynamic, 3>& x) const;
  /// x ~= A^-1 b with the float copy of L (relative error ~1e-6; ~1e-3 with the half copy): the
  /// solve is memory bound, and float halves the bytes read (half quarters them). Meant for
  /// preconditioning. Falls back to Solve when no float
  /// copy was kept or CHOLMOD chose a simplicial factor.
  void SolveSinglePrecision(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// x ~= R A^-1 R^T b with R block diagonal, node_rotations[i] on rows 3i..3i+2 (A's factor
  /// turned into other frames node by node: the rotated-factor preconditioner), with the float or
  /// half copy like SolveSinglePrecision; the turns ride on its permutations. Throws
  /// std::invalid_argument unless there is one rotation per 3 rows.
  void SolveSinglePrecisionTurned(const std::vector<Eigen::Matrix3d>& node_rotations, const Eigen::VectorXd& b,
                                  Eigen::VectorXd& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A factor being computed on a worker thread; a null result: the matrix is not positive definite.
using RestFactorFuture = std::shared_future<std::shared_ptr<const CholmodSolver>>;

}  // namespace vesica::physics
