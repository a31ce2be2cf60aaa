// The dense LAPACK solve behind the BEM's reference system, and the dense-algebra thread limit a
// real-time session puts on OpenBLAS (which CHOLMOD's factorisations share).

#include "physics/bem/dense_lu_solve.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "physics/bem/bem_errors.h"

namespace vesica::physics {
namespace {

TEST(DenseLuSolveTest, RecoversAKnownSolutionOfANonsymmetricSystem) {
  const int n = 120;
  Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n) + n * Eigen::MatrixXd::Identity(n, n);
  a(0, n - 1) = 7.0;  // not symmetric
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(n, 3);
  Eigen::MatrixXd b = a * x;
  Eigen::MatrixXd factors = a;
  const double rcond = SolveDenseInPlace(factors, b, "test system");
  EXPECT_LT((b - x).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(rcond, 0.1);  // diagonally dominant: well conditioned
}

TEST(DenseLuSolveTest, SingularSystemThrowsNamingIt) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Ones(4, 4);
  Eigen::MatrixXd b = Eigen::MatrixXd::Ones(4, 1);
  try {
    SolveDenseInPlace(a, b, "liver reference system");
    FAIL() << "a rank-one matrix was solved";
  } catch (const SingularSystemError& e) {
    EXPECT_NE(std::string(e.what()).find("liver reference system"), std::string::npos) << e.what();
  }
}

TEST(DenseLuSolveTest, ScopedThreadLimitHoldsForItsLifetimeAndRestores) {
  const int original = DenseLinearAlgebraThreads();
  SetDenseLinearAlgebraThreads(3);
  ASSERT_EQ(DenseLinearAlgebraThreads(), 3);
  {
    ScopedDenseLinearAlgebraThreads limit(1);
    EXPECT_EQ(DenseLinearAlgebraThreads(), 1);
    // A solve under the limit still solves.
    Eigen::MatrixXd a = 2.0 * Eigen::MatrixXd::Identity(300, 300);
    Eigen::MatrixXd b = Eigen::MatrixXd::Ones(300, 1);
    SolveDenseInPlace(a, b, "diagonal");
    EXPECT_DOUBLE_EQ(b(299, 0), 0.5);
  }
  EXPECT_EQ(DenseLinearAlgebraThreads(), 3);
  SetDenseLinearAlgebraThreads(0);  // clamped: at least one thread
  EXPECT_EQ(DenseLinearAlgebraThreads(), 1);
  SetDenseLinearAlgebraThreads(original);  // the tests after this one in the process
}

}  // namespace
}  // namespace vesica::physics
