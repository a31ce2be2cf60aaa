#include "physics/scene/constraint_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace vesica::physics {
namespace {

ConstraintProblem Single(double w, double soft, double gap, ConstraintKind kind) {
  ConstraintProblem p;
  p.delassus = Eigen::MatrixXd::Constant(1, 1, w);
  p.soft_compliance = Eigen::VectorXd::Constant(1, soft);
  p.gap = Eigen::VectorXd::Constant(1, gap);
  p.kinds = {kind};
  return p;
}

// A contact on a point held only by a spring k: W = 1/k, so lambda = max(0, -k delta).
TEST(ConstraintSolverTest, SpringSupportedContactGivesMaxZeroMinusKDelta) {
  const double k = 250.0;
  for (double delta : {-4e-3, -1e-3, -1e-6, 0.0, 1e-6, 2e-3}) {
    const ConstraintSolution s = SolveConstraints(Single(1.0 / k, 0.0, delta, ConstraintKind::kUnilateral));
    EXPECT_NEAR(s.lambda[0], std::max(0.0, -k * delta), 1e-12) << "delta " << delta;
    EXPECT_LE(s.max_error_m, 1e-12);
  }
}

// Soft constraints (registration paper eq. 6): compliances add in series.
TEST(ConstraintSolverTest, SoftComplianceAddsInSeries) {
  const ConstraintSolution s = SolveConstraints(Single(1e-3, 3e-3, -2e-3, ConstraintKind::kBilateral));
  EXPECT_NEAR(s.lambda[0], 2e-3 / 4e-3, 1e-12);
  // A bilateral row pulls as well as pushes.
  const ConstraintSolution pull = SolveConstraints(Single(1e-3, 0.0, 2e-3, ConstraintKind::kBilateral));
  EXPECT_NEAR(pull.lambda[0], -2.0, 1e-9);
}

TEST(ConstraintSolverTest, BilateralSystemMatchesDirectSolve) {
  Eigen::MatrixXd b = Eigen::MatrixXd::Random(6, 6);
  ConstraintProblem p;
  p.delassus = b * b.transpose() + 0.5 * Eigen::MatrixXd::Identity(6, 6);
  p.soft_compliance = Eigen::VectorXd::Constant(6, 0.1);
  p.gap = Eigen::VectorXd::Random(6);
  p.kinds.assign(6, ConstraintKind::kBilateral);
  const ConstraintSolution s = SolveConstraints(p, {.max_iterations = 5000, .tolerance_m = 1e-13});
  Eigen::MatrixXd a = p.delassus;
  a.diagonal() += p.soft_compliance;
  const Eigen::VectorXd expected = a.ldlt().solve(-p.gap);
  EXPECT_LT((s.lambda - expected).norm(), 1e-10 * expected.norm());
}

// Two coupled contacts where one separates: the LCP solution has lambda_2 = 0 and the first row
// solved alone; checked against enumeration of the active sets.
TEST(ConstraintSolverTest, UnilateralRowsSatisfyComplementarity) {
  ConstraintProblem p;
  p.delassus.resize(2, 2);
  p.delassus << 2.0, 1.0, 1.0, 2.0;
  p.soft_compliance = Eigen::VectorXd::Zero(2);
  p.gap = Eigen::Vector2d(-2.0, 0.5);
  p.kinds = {ConstraintKind::kUnilateral, ConstraintKind::kUnilateral};
  const ConstraintSolution s = SolveConstraints(p);
  EXPECT_NEAR(s.lambda[0], 1.0, 1e-12);  // 2 l1 - 2 = 0
  EXPECT_DOUBLE_EQ(s.lambda[1], 0.0);    // residual 1 * 1 + 0.5 > 0: separating
  const Eigen::VectorXd residual = p.delassus * s.lambda + p.gap;
  EXPECT_NEAR(residual[0], 0.0, 1e-12);
  EXPECT_GT(residual[1], 0.0);
}

TEST(ConstraintSolverTest, EmptyProblemHasNoForces) {
  ConstraintProblem p;
  EXPECT_EQ(SolveConstraints(p).lambda.size(), 0);
}

TEST(ConstraintSolverTest, BadInputNamesTheProblem) {
  ConstraintProblem p = Single(1.0, 0.0, -1.0, ConstraintKind::kUnilateral);
  p.gap[0] = std::nan("");
  EXPECT_THROW(SolveConstraints(p), std::invalid_argument);
  p = Single(0.0, 0.0, -1.0, ConstraintKind::kUnilateral);
  try {
    SolveConstraints(p);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 0"), std::string::npos);
  }
  p = Single(1.0, -1.0, -1.0, ConstraintKind::kUnilateral);
  EXPECT_THROW(SolveConstraints(p), std::invalid_argument);
  p = Single(1.0, 0.0, -1.0, ConstraintKind::kUnilateral);
  p.kinds.clear();
  EXPECT_THROW(SolveConstraints(p), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics

namespace vesica::physics {
namespace {

// A point on a spring k in each direction (W = I/k, uncoupled) pressed delta_n into a surface and
// slipped delta_t along it: the normal force is -k delta_n; friction holds the slip (-k delta_t)
// up to mu times that, and slides at the bound beyond it.
ConstraintProblem NormalAndFriction(double k, double delta_n, double delta_t, double mu) {
  ConstraintProblem p;
  p.delassus = Eigen::MatrixXd::Identity(2, 2) / k;
  p.soft_compliance = Eigen::VectorXd::Zero(2);
  p.gap = Eigen::Vector2d(delta_n, delta_t);
  p.kinds = {ConstraintKind::kUnilateral, ConstraintKind::kFriction};
  p.normal_row = {-1, 0};
  p.friction_coefficient = {0.0, mu};
  return p;
}

TEST(ConstraintSolverTest, FrictionSticksInsideTheConeAndSlidesAtItsBound) {
  const double k = 100.0;
  const ConstraintSolution stick = SolveConstraints(NormalAndFriction(k, -2e-3, 0.5e-3, 0.4));
  EXPECT_NEAR(stick.lambda[0], 0.2, 1e-12);
  EXPECT_NEAR(stick.lambda[1], -0.05, 1e-12);  // |0.05| < 0.4 x 0.2: the slip is undone
  const ConstraintSolution slide = SolveConstraints(NormalAndFriction(k, -2e-3, -3e-3, 0.4));
  EXPECT_NEAR(slide.lambda[0], 0.2, 1e-12);
  EXPECT_NEAR(slide.lambda[1], 0.08, 1e-12);  // 0.3 N wanted, 0.4 x 0.2 N allowed
  const ConstraintSolution apart = SolveConstraints(NormalAndFriction(k, 1e-3, -3e-3, 0.4));
  EXPECT_EQ(apart.lambda[0], 0.0);
  EXPECT_EQ(apart.lambda[1], 0.0);  // no normal force, no friction
}

TEST(ConstraintSolverTest, FrictionRowWithoutANormalRowIsRefused) {
  ConstraintProblem p = NormalAndFriction(100.0, -1e-3, 0.0, 0.4);
  p.normal_row = {-1, 1};  // itself, not a unilateral row
  EXPECT_THROW(SolveConstraints(p), std::invalid_argument);
  p = NormalAndFriction(100.0, -1e-3, 0.0, -0.1);
  EXPECT_THROW(SolveConstraints(p), std::invalid_argument);
  p = NormalAndFriction(100.0, -1e-3, 0.0, 0.4);
  p.friction_coefficient.clear();
  EXPECT_THROW(SolveConstraints(p), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
