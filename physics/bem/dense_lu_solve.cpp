#include "physics/bem/dense_lu_solve.h"

#include <cstddef>
#include <vector>

#include "physics/bem/bem_errors.h"

extern "C" {
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dgetrs_(const char* trans, const int* n, const int* nrhs, const double* a, const int* lda, const int* ipiv,
             double* b, const int* ldb, int* info, std::size_t trans_len);
void dgecon_(const char* norm, const int* n, const double* a, const int* lda, const double* anorm, double* rcond,
             double* work, int* iwork, int* info, std::size_t norm_len);
char* openblas_get_config();
char* openblas_get_corename();
int openblas_get_num_threads();
void openblas_set_num_threads(int num_threads);
}

namespace vesica::physics {

double SolveDenseInPlace(Eigen::MatrixXd& A, Eigen::MatrixXd& B, const std::string& what, double min_rcond) {
  if (A.rows() != A.cols() || B.rows() != A.rows()) throw BemError(what + ": dense solve with mismatched sizes");
  const int n = static_cast<int>(A.rows());
  const int nrhs = static_cast<int>(B.cols());
  if (n == 0) return 1.0;
  const double anorm = A.cwiseAbs().colwise().sum().maxCoeff();
  std::vector<int> pivots(static_cast<std::size_t>(n));
  int info = 0;
  dgetrf_(&n, &n, A.data(), &n, pivots.data(), &info);
  if (info > 0) throw SingularSystemError(what + ": exactly singular (zero pivot at row " + std::to_string(info) + ")");
  double rcond = 0.0;
  std::vector<double> work(4 * static_cast<std::size_t>(n));
  std::vector<int> iwork(static_cast<std::size_t>(n));
  const char norm = '1';
  dgecon_(&norm, &n, A.data(), &n, &anorm, &rcond, work.data(), iwork.data(), &info, 1);
  if (!(rcond >= min_rcond))
    throw SingularSystemError(what + ": singular to working precision (reciprocal condition " + std::to_string(rcond) +
                              ")");
  const char trans = 'N';
  dgetrs_(&trans, &n, &nrhs, A.data(), &n, pivots.data(), B.data(), &n, &info, 1);
  return rcond;
}

std::string DenseLinearAlgebraBackend() {
  return std::string(openblas_get_config()) + " core " + openblas_get_corename();
}

int DenseLinearAlgebraThreads() { return openblas_get_num_threads(); }

void SetDenseLinearAlgebraThreads(int threads) { openblas_set_num_threads(threads < 1 ? 1 : threads); }

ScopedDenseLinearAlgebraThreads::ScopedDenseLinearAlgebraThreads(int threads) : previous_(DenseLinearAlgebraThreads()) {
  SetDenseLinearAlgebraThreads(threads);
}

ScopedDenseLinearAlgebraThreads::~ScopedDenseLinearAlgebraThreads() { SetDenseLinearAlgebraThreads(previous_); }

}  // namespace vesica::physics
