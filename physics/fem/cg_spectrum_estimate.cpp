#include "physics/fem/cg_spectrum_estimate.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace vesica::physics {

SpectrumEstimate EstimateSpectrumFromCg(std::span<const double> alphas, std::span<const double> betas) {
  const int m = static_cast<int>(alphas.size());
  if (m == 0 || static_cast<int>(betas.size()) < m - 1) return {};
  Eigen::VectorXd diagonal(m), off_diagonal(std::max(m - 1, 0));
  for (int j = 0; j < m; ++j) {
    diagonal[j] = 1.0 / alphas[j] + (j > 0 ? betas[j - 1] / alphas[j - 1] : 0.0);
    if (j + 1 < m) off_diagonal[j] = std::sqrt(betas[j]) / alphas[j];
  }
  if (!diagonal.allFinite() || !off_diagonal.allFinite()) return {};
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(diagonal, off_diagonal, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) return {};
  return {solver.eigenvalues()[0], solver.eigenvalues()[m - 1]};
}

}  // namespace vesica::physics
