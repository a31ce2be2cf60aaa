#include "physics/fem/cholmod_solver.h"

#include <algorithm>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

namespace vesica::physics {

struct CholmodSolver::Impl {
  Eigen::SparseMatrix<double> matrix;  // same structure as the pattern; values copied in
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> cholesky;
  bool analysed = false;
  bool factorized = false;
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>()) {}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::Factorize(const SparsePattern& pattern, const Eigen::VectorXd& values) {
  Impl& s = *impl_;
  if (!s.analysed || s.matrix.rows() != pattern.structure.rows() ||
      s.matrix.nonZeros() != pattern.structure.nonZeros()) {
    s.matrix = pattern.structure;
    s.cholesky.analyzePattern(s.matrix);
    s.analysed = true;
  }
  std::copy(values.data(), values.data() + values.size(), s.matrix.valuePtr());
  s.cholesky.factorize(s.matrix);
  s.factorized = s.cholesky.info() == Eigen::Success;
  return s.factorized;
}

bool CholmodSolver::factorized() const { return impl_->factorized; }

void CholmodSolver::Solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const { x = impl_->cholesky.solve(b); }

}  // namespace vesica::physics
