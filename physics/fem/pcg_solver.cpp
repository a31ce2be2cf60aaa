#include "physics/fem/pcg_solver.h"

#include <cmath>

#include <Eigen/LU>

#include "physics/fem/elastic_forces.h"

namespace vesica::physics {

void BlockJacobiPreconditioner::Compute(const SparsePattern& p, const Eigen::VectorXd& values) {
  const int nodes = static_cast<int>(p.structure.cols()) / 3;
  inverse_blocks_.resize(nodes);
  for (int i = 0; i < nodes; ++i) {
    Eigen::Matrix3d block;
    const int diag = p.diagonal_slot[3 * i];  // entry (3i, 3i); block columns are stride apart
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) block(r, c) = values[diag + c * p.column_stride[i] + r];
    inverse_blocks_[i] = block.inverse();
  }
}

void BlockJacobiPreconditioner::Apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  for (size_t i = 0; i < inverse_blocks_.size(); ++i) z.segment<3>(3 * i) = inverse_blocks_[i] * r.segment<3>(3 * i);
}

PcgResult SolvePcg(const SparsePattern& pattern, const Eigen::VectorXd& values, const Eigen::VectorXd& b,
                   Eigen::VectorXd& x, const Preconditioner& preconditioner, double relative_tolerance,
                   int max_iterations) {
  PcgResult result;
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    x.setZero(b.size());
    result.converged = true;
    return result;
  }
  if (x.size() != b.size()) x.setZero(b.size());
  Eigen::VectorXd r(b.size()), z, p, q;
  SymmetricPatternMultiply(pattern, values, x, q);
  r = b - q;
  const double target = relative_tolerance * b_norm;
  double r_norm = r.norm();
  if (r_norm <= target) {
    result.relative_residual = r_norm / b_norm;
    result.converged = true;
    return result;
  }
  preconditioner(r, z);
  p = z;
  double rz = r.dot(z);
  for (int it = 1; it <= max_iterations; ++it) {
    SymmetricPatternMultiply(pattern, values, p, q);
    const double pq = p.dot(q);
    if (!(pq > 0.0)) break;  // not positive definite along p (or NaN): stop, caller checks
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    result.iterations = it;
    r_norm = r.norm();
    if (r_norm <= target) break;
    preconditioner(r, z);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  result.relative_residual = r_norm / b_norm;
  result.converged = r_norm <= target;
  return result;
}

}  // namespace vesica::physics
