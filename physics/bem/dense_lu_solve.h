#pragma once
// Large dense LU solves through LAPACK (OpenBLAS: blocked and multithreaded), kept out of the
// headers so that only one translation unit sees the Fortran interface.

#include <Eigen/Core>
#include <string>

namespace vesica::physics {

/// Overwrites B with A^{-1} B (A is destroyed: it holds the LU factors afterwards). Throws
/// SingularSystemError naming `what` when the reciprocal 1-norm condition number of A is below
/// `min_rcond`. Returns that reciprocal condition number.
double SolveDenseInPlace(Eigen::MatrixXd& A, Eigen::MatrixXd& B, const std::string& what, double min_rcond = 1e-13);

/// The LAPACK backend and the CPU kernel it picked, e.g. "OpenBLAS 0.3.21 ... core SkylakeX".
/// OpenBLAS 0.3.21 does not recognise some virtual CPUs and falls back to "Prescott" (SSE3, ~4x
/// slower); set OPENBLAS_CORETYPE=SkylakeX (or Haswell) in the environment there.
std::string DenseLinearAlgebraBackend();

/// Threads the dense algebra (OpenBLAS: also CHOLMOD's supernodal factorisations, which call the
/// same library through libblas.so.3) may use; process-wide.
int DenseLinearAlgebraThreads();
/// Sets that number (at least 1). OpenBLAS's idle workers spin on sched_yield for a while after
/// every threaded call: right for a batch pre-process, wrong beside real-time loops on a small
/// machine, where they take the cores those need.
void SetDenseLinearAlgebraThreads(int threads);

/// Limits the dense algebra to `threads` for this object's lifetime, then restores the number it
/// found.
class ScopedDenseLinearAlgebraThreads {
 public:
  explicit ScopedDenseLinearAlgebraThreads(int threads);
  ~ScopedDenseLinearAlgebraThreads();
  ScopedDenseLinearAlgebraThreads(const ScopedDenseLinearAlgebraThreads&) = delete;
  ScopedDenseLinearAlgebraThreads& operator=(const ScopedDenseLinearAlgebraThreads&) = delete;

 private:
  int previous_;
};

}  // namespace vesica::physics
