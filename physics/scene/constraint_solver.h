#pragma once
// Lagrange-multiplier constraints with compliance (registration paper eqs. 4 and 6):
//   (W + W_soft) lambda + delta = 0          bilateral rows (grasps)
//   0 <= lambda  _|_  (W + W_soft) lambda + delta >= 0   unilateral rows (contacts)
// W = J C J^T is the Delassus operator (m/N) built from the bodies' compliances, W_soft a
// diagonal of per-row compliances (a grasp that gives), delta the gap (m) each row has before
// the constraint forces act: negative is penetration (unilateral) or violation (bilateral).
// A single unilateral row held only by a spring k has W = 1/k, so lambda = max(0, -k delta).

#include <Eigen/Core>
#include <vector>

namespace vesica::physics {

/// kFriction: a tangential row of a contact; its force is held to |lambda| <= mu lambda_normal
/// (Coulomb, per tangent direction: a pyramid for two tangents), sticking inside that bound.
enum class ConstraintKind { kUnilateral, kBilateral, kFriction };

struct ConstraintProblem {
  Eigen::MatrixXd delassus;         ///< W, m x m, symmetric positive semi-definite, m/N
  Eigen::VectorXd soft_compliance;  ///< W_soft diagonal, m entries >= 0, m/N
  Eigen::VectorXd gap;              ///< delta, m entries, metres
  std::vector<ConstraintKind> kinds;
  /// Friction rows only (others: ignored, may be empty when there are none): the unilateral row
  /// whose force bounds this one, and the friction coefficient mu >= 0.
  std::vector<int> normal_row;
  std::vector<double> friction_coefficient;
  /// Where the sweeps start (N, m entries; empty: zero): a warm start from the last step's forces,
  /// so a resting contact that barely changes needs a few sweeps instead of tens.
  Eigen::VectorXd initial_lambda;
};

struct ConstraintSolverSettings {
  int max_iterations = 200;    ///< projected Gauss-Seidel sweeps
  double tolerance_m = 1e-12;  ///< stop when no row's complementarity error exceeds this
  /// Problems over 32 rows read the symmetric W by columns (contiguous) and check convergence
  /// every 8th sweep: much faster for hundreds of rows, but other rounding than the row order,
  /// so it is asked for only where results need not match older runs bit for bit.
  bool fast_large_problems = false;
  /// > 0: also stop after a sweep in which no row's force moved its own row by more than this
  /// (|delta lambda_i| (W + W_soft)_ii, metres), a test that costs nothing; max_error_m is then
  /// computed once, after the last sweep. 0: only the complementarity test above.
  double change_tolerance_m = 0.0;
};

struct ConstraintSolution {
  Eigen::VectorXd lambda;  ///< N, one per row (>= 0 on unilateral rows)
  int iterations = 0;
  double max_error_m = 0;  ///< largest remaining violation of the row conditions, metres
};

/// Projected Gauss-Seidel on the rows (exact after one sweep for a single row; bilateral-only
/// problems converge like Gauss-Seidel on an SPD matrix). Throws std::invalid_argument on
/// mismatched sizes, non-finite entries, negative soft compliance or a row whose W + W_soft
/// diagonal is not positive (it could not be solved for).
ConstraintSolution SolveConstraints(const ConstraintProblem& problem, const ConstraintSolverSettings& settings = {});

}  // namespace vesica::physics
