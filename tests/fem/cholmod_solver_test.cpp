#include "physics/fem/cholmod_solver.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

#include "physics/fem/fem_model.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

// M/h^2 + K of a free gallbladder-sized box (h = 10 ms): symmetric positive definite.
Eigen::VectorXd SystemValues(const FemModel& m) {
  Eigen::VectorXd s = m.linear_stiffness_values;
  for (int i = 0; i < m.num_dofs(); ++i) s[m.pattern.diagonal_slot[i]] += 1e4 * m.lumped_mass_kg[i];
  return s;
}

FemModel Box(const Eigen::Vector3i& cells) {
  FemSettings s;
  s.material = {2300.0, 0.45, 1000.0};
  return BuildFemModel(MakeBoxTetMesh({0.08, 0.03, 0.03}, cells), s, {});
}

TEST(CholmodSolverTest, SolveInvertsTheMatrix) {
  const FemModel m = Box({8, 3, 3});
  const Eigen::VectorXd s = SystemValues(m);
  CholmodSolver cholesky;
  ASSERT_TRUE(cholesky.Factorize(m.pattern, s));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(m.num_dofs(), -1.0, 2.0);
  Eigen::VectorXd x;
  cholesky.Solve(b, x);
  EXPECT_LT((PatternMatrix(m.pattern, s) * x - b).norm(), 1e-12 * b.norm());
}

// A node's three unit forces in one solve: the same columns as three solves (to rounding).
TEST(CholmodSolverTest, ThreeColumnSolveMatchesThreeSingleSolves) {
  const FemModel m = Box({8, 3, 3});
  const Eigen::VectorXd s = SystemValues(m);
  CholmodSolver cholesky;
  ASSERT_TRUE(cholesky.Factorize(m.pattern, s));
  Eigen::Matrix<double, Eigen::Dynamic, 3> b(m.num_dofs(), 3), x;
  b.col(0) = Eigen::VectorXd::LinSpaced(m.num_dofs(), -1.0, 2.0);
  b.col(1) = Eigen::VectorXd::Unit(m.num_dofs(), 7);
  b.col(2) = b.col(0).cwiseAbs();
  cholesky.Solve(b, x);
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd single;
    cholesky.Solve(Eigen::VectorXd(b.col(c)), single);
    EXPECT_LT((x.col(c) - single).norm(), 1e-13 * single.norm()) << "column " << c;
    EXPECT_LT((PatternMatrix(m.pattern, s) * x.col(c) - b.col(c)).norm(), 1e-12 * b.col(c).norm()) << "column " << c;
  }
}

// A factor shared between threads (the FEM body's preconditioner and the scene's compliance
// worker): concurrent solves of both kinds give the answers a lone thread gets, bit for bit.
TEST(CholmodSolverTest, ConcurrentSolvesAgreeWithSerialOnes) {
  const FemModel m = Box({28, 9, 9});  // supernodal: the half copy exists
  CholmodSolver cholesky;
  ASSERT_TRUE(cholesky.Factorize(m.pattern, SystemValues(m), true, true));
  std::vector<Eigen::VectorXd> b(8);
  std::vector<Eigen::VectorXd> exact(8), half(8);
  for (int k = 0; k < 8; ++k) {
    b[k] = Eigen::VectorXd::LinSpaced(m.num_dofs(), -1.0 - k, 2.0 + k);
    cholesky.Solve(b[k], exact[k]);
    cholesky.SolveSinglePrecision(b[k], half[k]);
  }
  auto run = [&](bool low_precision, int& mismatches) {
    for (int round = 0; round < 20; ++round)
      for (int k = 0; k < 8; ++k) {
        Eigen::VectorXd x;
        if (low_precision)
          cholesky.SolveSinglePrecision(b[k], x);
        else
          cholesky.Solve(b[k], x);
        if (x != (low_precision ? half[k] : exact[k])) ++mismatches;
      }
  };
  int mismatches[4] = {0, 0, 0, 0};
  std::thread t0([&] { run(true, mismatches[0]); }), t1([&] { run(true, mismatches[1]); });
  std::thread t2([&] { run(false, mismatches[2]); }), t3([&] { run(false, mismatches[3]); });
  t0.join(), t1.join(), t2.join(), t3.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

// The float copy of a supernodal factor (the 2,900-node grid gets one) solves to float accuracy:
// a relative error of 1e-5 at most, and not exactly the double solve (the float path really ran).
TEST(CholmodSolverTest, SinglePrecisionSolveAgreesWithTheDoubleSolveToFloatAccuracy) {
  for (const Eigen::Vector3i& cells : {Eigen::Vector3i(8, 3, 3), Eigen::Vector3i(28, 9, 9)}) {
    const FemModel m = Box(cells);
    CholmodSolver cholesky;
    ASSERT_TRUE(cholesky.Factorize(m.pattern, SystemValues(m), true));
    Eigen::VectorXd b(m.num_dofs());
    for (int i = 0; i < m.num_dofs(); ++i) b[i] = std::sin(0.37 * i) + 0.1 * (i % 3);
    Eigen::VectorXd exact, single;
    cholesky.Solve(b, exact);
    cholesky.SolveSinglePrecision(b, single);
    const double error = (single - exact).norm() / exact.norm();
    EXPECT_LT(error, 1e-5) << cells.transpose();
    if (cells.x() == 28) {
      EXPECT_GT(error, 0.0);
    }
  }
}

// The half copy (binary16 times a power of two, solved in float) to half accuracy, for systems
// scaled by 1e-8 and 1e8 too: without the power-of-two scale their factors would underflow or
// overflow binary16 (largest 65504, smallest normal 6e-5).
TEST(CholmodSolverTest, HalfPrecisionSolveAgreesWithTheDoubleSolveToHalfAccuracy) {
  const FemModel m = Box({28, 9, 9});
  for (double scale : {1.0, 1e-8, 1e8}) {
    CholmodSolver cholesky;
    ASSERT_TRUE(cholesky.Factorize(m.pattern, scale * SystemValues(m), true, true));
    if (!cholesky.half_storage()) GTEST_SKIP() << "no F16C on this CPU: the float copy is kept instead";
    Eigen::VectorXd b(m.num_dofs());
    for (int i = 0; i < m.num_dofs(); ++i) b[i] = std::sin(0.37 * i) + 0.1 * (i % 3);
    Eigen::VectorXd exact, half;
    cholesky.Solve(b, exact);
    cholesky.SolveSinglePrecision(b, half);
    const double error = (half - exact).norm() / exact.norm();
    std::printf("half-precision factor, system scaled by %g: relative error %.2e\n", scale, error);
    // ~1.6e-4 with the partitioned inverse in half (the factor itself in half, solved by
    // substitution: ~4.5e-4; with its 4 x 4 triangles inverted in float: ~2.0e-4).
    EXPECT_LT(error, 5e-4) << "scale " << scale;
    EXPECT_GT(error, 1e-5) << "scale " << scale;  // not the float copy
  }
}

// The bytes a low-precision solve streams: none without a copy; the half copy, in tiles without
// the zero upper triangles CHOLMOD's layout keeps (but with ~2.5 % of tile padding), somewhat
// under half the float copy's bytes; and at least 2 bytes for each entry of the factor's lower
// triangle (the factor of a box of 2,900 nodes has over 2 million).
TEST(CholmodSolverTest, LowPrecisionBytesAreTheCopysBytes) {
  const FemModel m = Box({28, 9, 9});
  CholmodSolver none, single, half;
  ASSERT_TRUE(none.Factorize(m.pattern, SystemValues(m)));
  ASSERT_TRUE(single.Factorize(m.pattern, SystemValues(m), true, false));
  ASSERT_TRUE(half.Factorize(m.pattern, SystemValues(m), true, true));
  if (!half.half_storage()) GTEST_SKIP() << "no F16C on this CPU: the float copy is kept instead";
  EXPECT_EQ(none.low_precision_bytes(), 0u);
  const double float_bytes = static_cast<double>(single.low_precision_bytes());
  const double half_bytes = static_cast<double>(half.low_precision_bytes());
  std::printf("low-precision factor bytes: float %.3g, half %.3g\n", float_bytes, half_bytes);
  EXPECT_LT(half_bytes, 0.5 * float_bytes);
  EXPECT_GT(half_bytes, 0.35 * float_bytes);
  EXPECT_GT(half_bytes, 2.0 * 2e6);
}

// PCG needs a symmetric preconditioner: the forward and backward solves of the half copy must use
// the same stored factor (the same T and W in both), so that a.P b = b.P a to float rounding
// (measured 1.4e-8); a backward solve whose inverses were 1e-4 off gave 3e-6.
TEST(CholmodSolverTest, HalfPrecisionSolveIsASymmetricOperator) {
  const FemModel m = Box({28, 9, 9});
  CholmodSolver cholesky;
  ASSERT_TRUE(cholesky.Factorize(m.pattern, SystemValues(m), true, true));
  if (!cholesky.half_storage()) GTEST_SKIP() << "no F16C on this CPU: the float copy is kept instead";
  Eigen::VectorXd a(m.num_dofs()), b(m.num_dofs());
  for (int i = 0; i < m.num_dofs(); ++i)
    a[i] = std::sin(0.37 * i) + 0.1 * (i % 3), b[i] = std::cos(1.3 * i) - 0.2 * (i % 5);
  Eigen::VectorXd pa, pb;
  cholesky.SolveSinglePrecision(a, pa);
  cholesky.SolveSinglePrecision(b, pb);
  // Against the Cauchy-Schwarz bound of a.P b in P's own inner product.
  const double asymmetry = std::abs(a.dot(pb) - b.dot(pa)) / std::sqrt(a.dot(pa) * b.dot(pb));
  std::printf("half-precision preconditioner: |a.P b - b.P a| / sqrt(a.P a b.P b) = %.2e\n", asymmetry);
  EXPECT_LT(asymmetry, 1e-7);
}

// A solve of a non-finite right-hand side (a diverging step's residual) leaves nothing behind: the
// next solve of a finite one is bit for bit a fresh solver's (the half kernels' work rows past a
// supernode meet zero tiles, and 0 x NaN would be NaN).
TEST(CholmodSolverTest, LowPrecisionSolveAfterANonFiniteOneIsUnaffected) {
  const FemModel m = Box({28, 9, 9});
  for (const bool half : {true, false}) {
    CholmodSolver used, fresh;
    ASSERT_TRUE(used.Factorize(m.pattern, SystemValues(m), true, half));
    ASSERT_TRUE(fresh.Factorize(m.pattern, SystemValues(m), true, half));
    Eigen::VectorXd b(m.num_dofs()), x, expected;
    for (int i = 0; i < m.num_dofs(); ++i) b[i] = std::sin(0.37 * i) + 0.1 * (i % 3);
    Eigen::VectorXd poisoned = b;
    poisoned[m.num_dofs() / 2] = std::numeric_limits<double>::quiet_NaN();
    used.SolveSinglePrecision(poisoned, x);
    EXPECT_FALSE(x.allFinite()) << "half " << half;
    used.SolveSinglePrecision(b, x);
    fresh.SolveSinglePrecision(b, expected);
    EXPECT_TRUE(x.allFinite()) << "half " << half;
    EXPECT_EQ(x, expected) << "half " << half;
  }
}

// The turned solve R A^-1 R^T b is the turn, the low-precision solve and the turn back, bit for
// bit, with the half copy, the float copy and (no copy kept) the double solve; and it inverts
// R A R^T: with the double solve to 1e-12, since R is orthogonal.
TEST(CholmodSolverTest, TurnedSolveIsTurnSolveTurnBack) {
  const FemModel m = Box({6, 3, 2});
  const Eigen::VectorXd s = SystemValues(m);
  std::vector<Eigen::Matrix3d> rotations(m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i)
    rotations[i] = Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(1.0, 0.5 * i, -2.0).normalized()).toRotationMatrix();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(m.num_dofs(), -1.0, 2.0).array().sin();
  auto turn = [&](const Eigen::VectorXd& v, bool transposed) {  // the preconditioner's turns before
    Eigen::VectorXd out(v.size());
    for (int i = 0; i < m.num_nodes(); ++i) {
      if (transposed)
        out.segment<3>(3 * i) = rotations[i].transpose() * v.segment<3>(3 * i);
      else
        out.segment<3>(3 * i) = rotations[i] * v.segment<3>(3 * i);
    }
    return out;
  };
  for (int copy = 0; copy < 3; ++copy) {  // half, float, none
    CholmodSolver cholesky;
    ASSERT_TRUE(cholesky.Factorize(m.pattern, s, copy < 2, copy == 0));
    Eigen::VectorXd turned, solved;
    cholesky.SolveSinglePrecisionTurned(rotations, b, turned);
    cholesky.SolveSinglePrecision(turn(b, true), solved);
    EXPECT_EQ(turned, turn(solved, false)) << "copy " << copy;
    if (copy == 2) {
      const Eigen::MatrixXd a = PatternMatrix(m.pattern, s);
      Eigen::MatrixXd r = Eigen::MatrixXd::Zero(m.num_dofs(), m.num_dofs());
      for (int i = 0; i < m.num_nodes(); ++i) r.block<3, 3>(3 * i, 3 * i) = rotations[i];
      EXPECT_LT((r * a * r.transpose() * turned - b).norm(), 1e-12 * b.norm());
    }
  }
  CholmodSolver cholesky;
  ASSERT_TRUE(cholesky.Factorize(m.pattern, s, true, true));
  Eigen::VectorXd x;
  rotations.pop_back();
  EXPECT_THROW(cholesky.SolveSinglePrecisionTurned(rotations, b, x), std::invalid_argument);
}

TEST(CholmodSolverTest, SinglePrecisionSolveWithoutAFloatCopyIsTheDoubleSolve) {
  const FemModel m = Box({8, 3, 3});
  CholmodSolver cholesky;
  ASSERT_TRUE(cholesky.Factorize(m.pattern, SystemValues(m)));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(m.num_dofs(), -1.0, 2.0);
  Eigen::VectorXd exact, single;
  cholesky.Solve(b, exact);
  cholesky.SolveSinglePrecision(b, single);
  EXPECT_EQ(single, exact);
}

// Negative definite: CHOLMOD stops at the first column (Eigen alone would report success).
TEST(CholmodSolverTest, IndefiniteMatrixIsReportedNotFactorised) {
  const FemModel m = Box({4, 2, 2});
  Eigen::VectorXd s = -SystemValues(m);
  CholmodSolver cholesky;
  EXPECT_FALSE(cholesky.Factorize(m.pattern, s, true));
  EXPECT_FALSE(cholesky.factorized());
}

int ThreadsOfThisProcess() {
  int threads = 0;
  for ([[maybe_unused]] const auto& task : std::filesystem::directory_iterator("/proc/self/task")) ++threads;
  return threads;
}

// CHOLMOD 5.12 asks OpenMP for 4 threads in its supernodal loops whatever OMP_NUM_THREADS says; on
// 2 cores their fork and join took 4x the factorisation. Ours runs them serially: no OpenMP worker
// thread appears (libgomp keeps its workers, so a parallel region would leave them in /proc), the
// factor is still right, and the caller's OpenMP setting comes back.
TEST(CholmodSolverTest, FactorisationStartsNoOpenMpThreadsAndRestoresTheCallersSetting) {
  using GetLevels = int (*)();
  using SetLevels = void (*)(int);
  const auto get_levels = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  const auto set_levels = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  ASSERT_NE(get_levels, nullptr) << "CHOLMOD's OpenMP runtime is not loaded: nothing to test";
  set_levels(3);
  const FemModel m = Box({20, 6, 6});  // supernodes wide enough for CHOLMOD's parallel loops
  const Eigen::VectorXd s = SystemValues(m);
  const int before = ThreadsOfThisProcess();
  CholmodSolver cholesky;
  ASSERT_TRUE(cholesky.Factorize(m.pattern, s));
  ASSERT_TRUE(cholesky.Factorize(m.pattern, 2.0 * s));
  EXPECT_EQ(ThreadsOfThisProcess(), before);
  EXPECT_EQ(get_levels(), 3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(m.num_dofs(), -1.0, 2.0);
  Eigen::VectorXd x;
  cholesky.Solve(b, x);
  EXPECT_LT((2.0 * (PatternMatrix(m.pattern, s) * x) - b).norm(), 1e-12 * b.norm());
}

}  // namespace
}  // namespace vesica::physics
