#include "physics/scene/constraint_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

namespace {
void Check(const ConstraintProblem& p) {
  const Eigen::Index m = p.gap.size();
  if (p.delassus.rows() != m || p.delassus.cols() != m || p.soft_compliance.size() != m ||
      static_cast<Eigen::Index>(p.kinds.size()) != m)
    throw std::invalid_argument("SolveConstraints: W is " + std::to_string(p.delassus.rows()) + "x" +
                                std::to_string(p.delassus.cols()) + ", W_soft has " +
                                std::to_string(p.soft_compliance.size()) + ", kinds " + std::to_string(p.kinds.size()) +
                                ", gaps " + std::to_string(m) + " entries");
  if (!p.delassus.allFinite() || !p.gap.allFinite() || !p.soft_compliance.allFinite())
    throw std::invalid_argument("SolveConstraints: non-finite W, W_soft or gap");
  if (p.initial_lambda.size() != 0 && (p.initial_lambda.size() != m || !p.initial_lambda.allFinite()))
    throw std::invalid_argument("SolveConstraints: initial_lambda has " + std::to_string(p.initial_lambda.size()) +
                                " entries (not finite, or not one per row: " + std::to_string(m) + ")");
  for (Eigen::Index i = 0; i < m; ++i) {
    if (p.kinds[static_cast<size_t>(i)] == ConstraintKind::kFriction) {
      const size_t k = static_cast<size_t>(i);
      if (p.normal_row.size() != static_cast<size_t>(m) || p.friction_coefficient.size() != static_cast<size_t>(m))
        throw std::invalid_argument(
            "SolveConstraints: friction rows need normal_row and friction_coefficient for every row");
      if (p.normal_row[k] < 0 || p.normal_row[k] >= m ||
          p.kinds[static_cast<size_t>(p.normal_row[k])] != ConstraintKind::kUnilateral)
        throw std::invalid_argument("SolveConstraints: friction row " + std::to_string(i) +
                                    " names no unilateral row as its normal (" + std::to_string(p.normal_row[k]) + ")");
      if (!(p.friction_coefficient[k] >= 0.0) || !std::isfinite(p.friction_coefficient[k]))
        throw std::invalid_argument("SolveConstraints: friction row " + std::to_string(i) +
                                    " has a friction coefficient that is not finite and >= 0");
    }
    if (p.soft_compliance[i] < 0.0)
      throw std::invalid_argument("SolveConstraints: row " + std::to_string(i) + " has negative soft compliance");
    if (!(p.delassus(i, i) + p.soft_compliance[i] > 0.0))
      throw std::invalid_argument("SolveConstraints: row " + std::to_string(i) +
                                  " has no compliance (W_ii + W_soft_ii <= 0): nothing can move to satisfy it");
  }
}

// Violation of row i's condition at the current lambda (0 when satisfied). A friction row at its
// bound slides: any residual is allowed there; inside it the row sticks exactly.
double RowError(ConstraintKind kind, double lambda, double residual, double bound = 0) {
  if (kind == ConstraintKind::kBilateral) return std::abs(residual);
  if (kind == ConstraintKind::kFriction) return std::abs(lambda) >= bound ? 0.0 : std::abs(residual);
  // Complementarity: a pushing row must close its gap exactly; an idle one must not penetrate.
  return lambda > 0.0 ? std::abs(residual) : std::max(0.0, -residual);
}

// Problems larger than this read A by columns in the sweep (see SolveConstraints).
constexpr Eigen::Index kContiguousRows = 32;

// mu lambda_normal for a friction row (0 for other rows).
double FrictionBound(const ConstraintProblem& p, const Eigen::VectorXd& lambda, Eigen::Index i) {
  if (p.kinds[static_cast<size_t>(i)] != ConstraintKind::kFriction) return 0.0;
  return p.friction_coefficient[static_cast<size_t>(i)] * lambda[p.normal_row[static_cast<size_t>(i)]];
}
}  // namespace

ConstraintSolution SolveConstraints(const ConstraintProblem& p, const ConstraintSolverSettings& settings) {
  Check(p);
  const Eigen::Index m = p.gap.size();
  ConstraintSolution out;
  out.lambda.setZero(m);
  if (m == 0) return out;
  if (p.initial_lambda.size() == m) out.lambda = p.initial_lambda;
  const bool large = settings.fast_large_problems && m > kContiguousRows;
  // A = W + W_soft; a large problem reads W itself and adds W_soft's diagonal as it goes (no copy
  // of hundreds of rows squared each step).
  Eigen::MatrixXd copy;
  if (!large) {
    copy = p.delassus;
    copy.diagonal() += p.soft_compliance;
  }
  const Eigen::MatrixXd& a = large ? p.delassus : copy;
  const Eigen::VectorXd diagonal =
      large ? Eigen::VectorXd(p.delassus.diagonal() + p.soft_compliance) : Eigen::VectorXd(copy.diagonal());
  const bool by_change = settings.change_tolerance_m > 0.0;
  auto max_error = [&] {
    Eigen::VectorXd residual = a * out.lambda + p.gap;
    if (large) residual += p.soft_compliance.cwiseProduct(out.lambda);
    double e = 0.0;
    for (Eigen::Index i = 0; i < m; ++i)
      e = std::max(
          e, RowError(p.kinds[static_cast<size_t>(i)], out.lambda[i], residual[i], FrictionBound(p, out.lambda, i)));
    return e;
  };
  for (int sweep = 1; sweep <= settings.max_iterations; ++sweep) {
    double largest_change_m = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      // Row residual without row i's own contribution, then the row's exact solution, projected.
      // A is symmetric: a large problem reads column i (contiguous) instead of row i (one cache
      // line per entry: 1 ms a sweep at m = 445, the freed gallbladder lying flat on an organ).
      // Asked for only after the freeing (ConstraintSolverSettings::fast_large_problems).
      const double row_dot =
          large ? a.col(i).dot(out.lambda) + p.soft_compliance[i] * out.lambda[i] : a.row(i).dot(out.lambda);
      const double others = row_dot - diagonal[i] * out.lambda[i] + p.gap[i];
      double li = -others / diagonal[i];
      const ConstraintKind kind = p.kinds[static_cast<size_t>(i)];
      if (kind == ConstraintKind::kUnilateral) li = std::max(0.0, li);
      if (kind == ConstraintKind::kFriction) {
        const double bound = FrictionBound(p, out.lambda, i);
        li = std::clamp(li, -bound, bound);
      }
      if (by_change) largest_change_m = std::max(largest_change_m, std::abs(li - out.lambda[i]) * diagonal[i]);
      out.lambda[i] = li;
    }
    out.iterations = sweep;
    if (by_change) {
      if (largest_change_m > settings.change_tolerance_m && sweep != settings.max_iterations) continue;
      out.max_error_m = max_error();
      if (largest_change_m <= settings.change_tolerance_m || out.max_error_m <= settings.tolerance_m) break;
      continue;
    }
    // A large problem checks convergence every 8th sweep and at the last (the check costs a sweep).
    if (large && sweep % 8 != 0 && sweep != settings.max_iterations) continue;
    out.max_error_m = max_error();
    if (out.max_error_m <= settings.tolerance_m) break;
  }
  return out;
}

}  // namespace vesica::physics
