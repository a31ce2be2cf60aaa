#pragma once
// Sparse Cholesky of a symmetric positive definite pattern matrix through SuiteSparse CHOLMOD.
// The symbolic analysis is done once per pattern; numeric factorisations reuse it.

#include <memory>

#include <Eigen/Core>

#include "physics/fem/sparse_pattern.h"

namespace vesica::physics {

class CholmodSolver {
 public:
  CholmodSolver();
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Factorises A (values in pattern order). Returns false when A is not positive definite.
  bool Factorize(const SparsePattern& pattern, const Eigen::VectorXd& values);
  bool factorized() const;
  /// x = A^-1 b with the last successful factorisation.
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vesica::physics
