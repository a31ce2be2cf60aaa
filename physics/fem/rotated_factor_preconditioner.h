#pragma once
// The preconditioner of LinearSolverKind::kRotatedFactorPcg: the rest system's factor turned into
// the current frame per node, z = R S0^-1 R^T r, optionally wrapped in block Gauss-Seidel sweeps
// on the step's system S and in exact solves on the nodes whose tets turn most apart
// (LocalBlockCorrection). Applied in the order forward sweeps, local solve, turned factor, local
// solve, backward sweeps: a palindrome, so the preconditioner is symmetric (and positive
// definite) for PCG.

#include <Eigen/Core>
#include <vector>

#include "physics/fem/sparse_pattern.h"

namespace vesica::physics {

class CholmodSolver;
class FloatBlockRows;
class LocalBlockCorrection;

/// What one application reads; the pointers outlive it.
struct RotatedFactorParts {
  const CholmodSolver* rest_factor = nullptr;  ///< factor of S0
  bool single_precision = true;                ///< the factor's low-precision solve
  const std::vector<Eigen::Matrix3d>* node_rotations = nullptr;
  /// Gauss-Seidel: this many forward sweeps before and backward sweeps after (0: none) on S, the
  /// double values on `pattern`, or `float_rows` (S rounded to float) when given.
  int sweeps = 0;
  const SparsePattern* pattern = nullptr;
  const Eigen::VectorXd* system_values = nullptr;
  const FloatBlockRows* float_rows = nullptr;
  const std::vector<Eigen::Matrix3d>* inverse_diagonal = nullptr;  ///< S's 3x3 diagonal blocks inverted
  const LocalBlockCorrection* local = nullptr;                     ///< null or empty: none
};

class RotatedFactorPreconditioner {
 public:
  /// z = P r.
  void Apply(const RotatedFactorParts& parts, const Eigen::VectorXd& r, Eigen::VectorXd& z);

 private:
  void ApplyTurnedFactor(const RotatedFactorParts& parts, const Eigen::VectorXd& r, Eigen::VectorXd& z);
  void ForwardSweepFromZero(const RotatedFactorParts& parts, const Eigen::VectorXd& r, Eigen::VectorXd& x,
                            Eigen::VectorXd& upper_times_x) const;
  // Scratch, kept between applications (no allocation in PCG's loop).
  Eigen::VectorXd turned_residual_, turned_solution_, residual_, correction_, sweep_residual_;
};

}  // namespace vesica::physics
