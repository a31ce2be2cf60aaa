#include "physics/fem/pcg_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "physics/fem/block_rows_simd.h"
#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_model.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

// M/h^2 + K of a small free box (h = 10 ms), symmetric positive definite, as pattern values.
struct SmallSystem {
  FemModel model;
  Eigen::VectorXd values;
  Eigen::MatrixXd dense;
};

SmallSystem MakeSystem() {
  FemSettings s;
  s.material = {2300.0, 0.45, 1000.0};
  SmallSystem sys{BuildFemModel(MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2}), s, {}), {}, {}};
  sys.values = sys.model.linear_stiffness_values;
  for (int i = 0; i < sys.model.num_dofs(); ++i)
    sys.values[sys.model.pattern.diagonal_slot[i]] += 1e4 * sys.model.lumped_mass_kg[i];
  sys.dense = Eigen::MatrixXd(PatternMatrix(sys.model.pattern, sys.values));
  return sys;
}

// Block lower part L (node j < node i), diagonal blocks D, upper part U of the dense matrix.
Eigen::MatrixXd BlockPart(const Eigen::MatrixXd& a, int part) {  // -1 lower, 0 diagonal, 1 upper
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(a.rows(), a.cols());
  for (int r = 0; r < a.rows(); ++r)
    for (int c = 0; c < a.cols(); ++c) {
      const int side = (c / 3 > r / 3) - (c / 3 < r / 3);
      if (side == part) out(r, c) = a(r, c);
    }
  return out;
}

Eigen::VectorXd TestVector(int n) {
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.3 * i) + 0.2;
  return b;
}

TEST(PcgSolverTest, GaussSeidelSweepsAreTheBlockTriangularSolves) {
  const SmallSystem sys = MakeSystem();
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(sys.model.pattern, sys.values);
  const Eigen::VectorXd b = TestVector(sys.model.num_dofs());
  const Eigen::MatrixXd d = BlockPart(sys.dense, 0), l = BlockPart(sys.dense, -1), u = BlockPart(sys.dense, 1);
  // Forward from zero: (D + L)^-1 b.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  BlockGaussSeidelSweep(sys.model.pattern, sys.values, jacobi.inverse_blocks(), b, x, true);
  const Eigen::MatrixXd dl = d + l, du = d + u;
  const Eigen::VectorXd forward = dl.partialPivLu().solve(b);  // block triangular: its 3x3 diagonal blocks are full
  EXPECT_LT((x - forward).norm(), 1e-12 * forward.norm());
  // -U x is then the residual b - A x.
  Eigen::VectorXd ux;
  UpperBlocksTimes(sys.model.pattern, sys.values, x, ux);
  EXPECT_LT((ux - u * x).norm(), 1e-12 * (u * x).norm());
  EXPECT_LT((b - sys.dense * x + ux).norm(), 1e-10 * b.norm());
  // The fused pass gives both at once.
  Eigen::VectorXd fused_x, fused_ux;
  ForwardSweepFromZeroAndUpperTimes(sys.model.pattern, sys.values, jacobi.inverse_blocks(), b, fused_x, fused_ux);
  EXPECT_LT((fused_x - forward).norm(), 1e-12 * forward.norm());
  EXPECT_LT((fused_ux - u * forward).norm(), 1e-12 * (u * forward).norm());
  // Backward from x0: x0 + (D + U)^-1 (b - A x0).
  const Eigen::VectorXd x0 = x;
  BlockGaussSeidelSweep(sys.model.pattern, sys.values, jacobi.inverse_blocks(), b, x, false);
  const Eigen::VectorXd backward = x0 + du.partialPivLu().solve(b - sys.dense * x0);
  EXPECT_LT((x - backward).norm(), 1e-12 * backward.norm());
}

// The AVX2 + FMA block-row kernels called directly (the public functions pick them on such a CPU
// unless VESICA_FEM_ELEMENT_KERNEL=scalar, so with the variable set the test above checks the
// portable loops and this one still checks the kernels), against the dense products and solves.
TEST(PcgSolverTest, Avx2BlockRowKernelsAreTheDenseProductAndTriangularSolves) {
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) GTEST_SKIP() << "no AVX2 + FMA";
  const SmallSystem sys = MakeSystem();
  const SparsePattern& p = sys.model.pattern;
  const int nodes = sys.model.num_nodes();
  BlockRowsView view;
  view.nodes = nodes;
  view.outer = p.structure.outerIndexPtr();
  view.inner = p.structure.innerIndexPtr();
  view.column_stride = p.column_stride.data();
  view.diagonal_slot = p.diagonal_slot.data();
  view.values = sys.values.data();
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(p, sys.values);
  const double* inverse = jacobi.inverse_blocks().data()->data();
  const Eigen::VectorXd b = TestVector(sys.model.num_dofs());
  std::vector<double> scratch(BlockRowSweepScratch(nodes) + 1);  // +1: run from an odd address too
  const Eigen::MatrixXd d = BlockPart(sys.dense, 0), l = BlockPart(sys.dense, -1), u = BlockPart(sys.dense, 1);

  Eigen::VectorXd y(b.size());
  SymmetricPatternMultiplyAvx2(view, b.data(), y.data());
  EXPECT_LT((y - sys.dense * b).norm(), 1e-13 * (sys.dense * b).norm());

  for (int offset : {0, 1}) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), ux = Eigen::VectorXd::Zero(b.size());
    ForwardSweepFromZeroAndUpperTimesAvx2(view, inverse, b.data(), x.data(), ux.data(), scratch.data() + offset);
    const Eigen::VectorXd forward = (d + l).partialPivLu().solve(b);
    EXPECT_LT((x - forward).norm(), 1e-12 * forward.norm());
    EXPECT_LT((ux - u * forward).norm(), 1e-12 * (u * forward).norm());
    Eigen::VectorXd sweep = Eigen::VectorXd::Zero(b.size());
    BlockGaussSeidelSweepAvx2(view, inverse, b.data(), sweep.data(), true, scratch.data() + offset);
    EXPECT_LT((sweep - forward).norm(), 1e-12 * forward.norm());
    const Eigen::VectorXd x0 = 0.5 * forward + TestVector(b.size()) * 1e-3;
    Eigen::VectorXd back = x0;
    BlockGaussSeidelSweepAvx2(view, inverse, b.data(), back.data(), false, scratch.data() + offset);
    const Eigen::VectorXd backward = x0 + (d + u).partialPivLu().solve(b - sys.dense * x0);
    EXPECT_LT((back - backward).norm(), 1e-12 * backward.norm());
  }
}

// The sweeps on the float node-block rows are the block triangular solves of the matrix whose
// off-diagonal blocks are rounded to float (the diagonal blocks' inverses stay double).
TEST(PcgSolverTest, FloatBlockRowSweepsAreTheTriangularSolvesOfTheRoundedMatrix) {
  if (!FloatBlockRows::available()) GTEST_SKIP() << "no AVX2 + FMA (or VESICA_FEM_ELEMENT_KERNEL=scalar)";
  const SmallSystem sys = MakeSystem();
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(sys.model.pattern, sys.values);
  FloatBlockRows rows;
  rows.Update(sys.model.pattern, 0.5 * sys.values);  // structure built, then values replaced
  rows.Update(sys.model.pattern, sys.values);
  Eigen::MatrixXd rounded = sys.dense;
  for (int r = 0; r < rounded.rows(); ++r)
    for (int c = 0; c < rounded.cols(); ++c)
      if (r / 3 != c / 3) rounded(r, c) = static_cast<float>(rounded(r, c));
  EXPECT_GT((rounded - sys.dense).norm(), 0.0);
  const Eigen::MatrixXd d = BlockPart(sys.dense, 0), l = BlockPart(rounded, -1), u = BlockPart(rounded, 1);
  const Eigen::VectorXd b = TestVector(sys.model.num_dofs());
  Eigen::VectorXd x, ux;
  ForwardSweepFromZeroAndUpperTimes(rows, jacobi.inverse_blocks(), b, x, ux);
  const Eigen::VectorXd forward = (d + l).partialPivLu().solve(b);
  EXPECT_LT((x - forward).norm(), 1e-12 * forward.norm());
  EXPECT_LT((ux - u * forward).norm(), 1e-12 * (u * forward).norm());
  Eigen::VectorXd sweep = Eigen::VectorXd::Zero(b.size());
  BlockGaussSeidelSweep(rows, jacobi.inverse_blocks(), b, sweep, true);
  EXPECT_LT((sweep - forward).norm(), 1e-12 * forward.norm());
  const Eigen::VectorXd x0 = 0.5 * forward + 1e-3 * TestVector(b.size());
  Eigen::VectorXd back = x0;
  BlockGaussSeidelSweep(rows, jacobi.inverse_blocks(), b, back, false);
  const Eigen::VectorXd backward = x0 + (d + u).partialPivLu().solve(b - (d + l + u) * x0);
  EXPECT_LT((back - backward).norm(), 1e-12 * backward.norm());
  // Not the double matrix's sweep (the rounding is seen).
  Eigen::VectorXd exact = Eigen::VectorXd::Zero(b.size());
  BlockGaussSeidelSweep(sys.model.pattern, sys.values, jacobi.inverse_blocks(), b, exact, true);
  EXPECT_GT((sweep - exact).norm(), 1e-14 * exact.norm());
}

// The float rows' map of the pattern's values is one to one onto the rows' values, writing through
// it is Update, rows read back are the matrix's rows rounded, and block Jacobi from the float rows
// is the double one's to float rounding.
TEST(PcgSolverTest, FloatBlockRowsMapEveryValueAndReadBackRowsAndDiagonalInverses) {
  const SmallSystem sys = MakeSystem();
  const SparsePattern& p = sys.model.pattern;
  FloatBlockRows updated, written;
  updated.Update(p, sys.values);
  written.Reshape(p);
  const std::vector<int> index = written.ValueIndexOfSlots(p);
  ASSERT_EQ(static_cast<Eigen::Index>(index.size()), p.structure.nonZeros());
  std::vector<int> hits(index.size(), 0);
  for (int i : index) {
    ASSERT_GE(i, 0);
    ASSERT_LT(i, static_cast<int>(index.size()));
    ++hits[i];
  }
  EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), static_cast<long>(hits.size()));
  for (size_t k = 0; k < index.size(); ++k) written.values()[index[k]] = static_cast<float>(sys.values[k]);
  for (size_t k = 0; k < index.size(); ++k) ASSERT_EQ(written.values()[k], updated.values()[k]) << k;

  for (int dof = 0; dof < sys.model.num_dofs(); ++dof) {
    std::vector<int> columns;
    std::vector<double> values;
    written.AppendRow(dof, columns, values);
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(sys.model.num_dofs());
    for (size_t k = 0; k < columns.size(); ++k) row[columns[k]] += values[k];
    Eigen::RowVectorXd rounded = sys.dense.row(dof).cast<float>().cast<double>();
    EXPECT_EQ((row - rounded).cwiseAbs().maxCoeff(), 0.0) << dof;
    EXPECT_EQ(static_cast<int>(columns.size()),
              p.structure.outerIndexPtr()[dof + 1] - p.structure.outerIndexPtr()[dof]);
  }

  BlockJacobiPreconditioner from_double, from_float;
  from_double.Compute(p, sys.values);
  from_float.Compute(written);
  double worst = 0.0;
  for (int n = 0; n < sys.model.num_nodes(); ++n) {
    const Eigen::Matrix3d& a = from_double.inverse_blocks()[n];
    worst = std::max(worst, (from_float.inverse_blocks()[n] - a).norm() / a.norm());
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(worst, 0.0);  // the rounding is seen
}

// PCG with block Jacobi on the small system from zero, right-hand side TestVector.
PcgResult SolveWithBlockJacobi(const SmallSystem& sys, double tolerance, int max_iterations, Eigen::VectorXd& x) {
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(sys.model.pattern, sys.values);
  x.resize(0);
  return SolvePcg(
      sys.model.pattern, sys.values, TestVector(sys.model.num_dofs()), x,
      [&](const Eigen::VectorXd& res, Eigen::VectorXd& z) { jacobi.Apply(res, z); }, tolerance, max_iterations);
}

TEST(PcgSolverTest, PcgWithBlockJacobiSolvesTheSystem) {
  const SmallSystem sys = MakeSystem();
  const Eigen::VectorXd b = TestVector(sys.model.num_dofs());
  Eigen::VectorXd x;
  const PcgResult r = SolveWithBlockJacobi(sys, 1e-12, 1000, x);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((sys.dense * x - b).norm(), 1e-11 * b.norm());
}

// The eigenvalues of P^-1 A for block Jacobi P: those of the pencil (A, P).
Eigen::VectorXd BlockJacobiPreconditionedSpectrum(const Eigen::MatrixXd& a) {
  const Eigen::MatrixXd p = BlockPart(a, 0);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> pencil(a, p, Eigen::EigenvaluesOnly);
  return pencil.eigenvalues();
}

TEST(PcgSolverTest, SpectrumEstimateConvergesToThePreconditionedSpectrumsEnds) {
  const SmallSystem sys = MakeSystem();
  const Eigen::VectorXd exact = BlockJacobiPreconditionedSpectrum(sys.dense);
  const double lowest = exact.minCoeff(), highest = exact.maxCoeff();
  ASSERT_GT(highest / lowest, 1.5);  // a spectrum with ends to find, not a point
  Eigen::VectorXd x;
  const PcgResult r = SolveWithBlockJacobi(sys, 1e-13, 1000, x);
  ASSERT_TRUE(r.converged);
  ASSERT_GT(r.iterations, 10);
  // The ends converge first, the lowest (in a cluster of low modes) slowest: 7.5e-6 off here.
  EXPECT_NEAR(r.spectrum.smallest, lowest, 1e-4 * lowest);
  EXPECT_NEAR(r.spectrum.largest, highest, 1e-4 * highest);
  EXPECT_NEAR(r.spectrum.condition(), highest / lowest, 2e-4 * highest / lowest);
}

TEST(PcgSolverTest, SpectrumEstimateOfAShortSolveLiesInsideTheSpectrum) {
  // Ritz values interlace: after a few iterations the estimate is an inner bound, not yet the ends.
  const SmallSystem sys = MakeSystem();
  const Eigen::VectorXd exact = BlockJacobiPreconditionedSpectrum(sys.dense);
  Eigen::VectorXd x;
  const PcgResult r = SolveWithBlockJacobi(sys, 1e-13, 3, x);
  ASSERT_EQ(r.iterations, 3);
  EXPECT_GE(r.spectrum.smallest, exact.minCoeff() * (1.0 - 1e-12));
  EXPECT_LE(r.spectrum.largest, exact.maxCoeff() * (1.0 + 1e-12));
  EXPECT_LT(r.spectrum.smallest, r.spectrum.largest);
  EXPECT_GT(r.spectrum.smallest - exact.minCoeff(), 1e-3 * exact.minCoeff());  // not converged yet
}

TEST(PcgSolverTest, SpectrumEstimateOfADiagonalSystemIsItsEigenvalues) {
  // A = diag(1, 2, ..., 6), no preconditioner, b touching every eigenvector: six iterations
  // span the whole space, and the Ritz values are the eigenvalues.
  const int n = 6;
  const MatrixOperator apply = [](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    out = in.cwiseProduct(Eigen::VectorXd::LinSpaced(6, 1.0, 6.0));
  };
  const Preconditioner identity = [](const Eigen::VectorXd& res, Eigen::VectorXd& z) { z = res; };
  Eigen::VectorXd x;
  const PcgResult r = SolvePcg(apply, Eigen::VectorXd::Ones(n), x, identity, 1e-14, n);
  EXPECT_EQ(r.iterations, n);
  EXPECT_NEAR(r.spectrum.smallest, 1.0, 1e-10);
  EXPECT_NEAR(r.spectrum.largest, 6.0, 1e-10);
  Eigen::VectorXd none;
  const PcgResult zero = SolvePcg(apply, Eigen::VectorXd::Zero(n), none, identity, 1e-14, n);
  EXPECT_EQ(zero.spectrum.smallest, 0.0);
  EXPECT_EQ(zero.spectrum.condition(), 0.0);
}

TEST(PcgSolverTest, GivenInitialProductReplacesTheFirstProduct) {
  // The warm start's product handed in must give the same iterates as PCG computing it, with one
  // product fewer.
  const SmallSystem sys = MakeSystem();
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(sys.model.pattern, sys.values);
  const Eigen::VectorXd b = TestVector(sys.model.num_dofs());
  const Eigen::VectorXd start = 0.5 * sys.dense.ldlt().solve(b);
  int products = 0;
  const MatrixOperator apply = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    ++products;
    SymmetricPatternMultiply(sys.model.pattern, sys.values, in, out);
  };
  const Preconditioner pre = [&](const Eigen::VectorXd& res, Eigen::VectorXd& z) { jacobi.Apply(res, z); };
  Eigen::VectorXd x_plain = start;
  const PcgResult plain = SolvePcg(apply, b, x_plain, pre, 1e-12, 1000);
  const int plain_products = products;
  products = 0;
  Eigen::VectorXd x_given = start;
  const Eigen::VectorXd start_product = sys.dense * start;
  const PcgResult given = SolvePcg(apply, b, x_given, pre, 1e-12, 1000, &start_product);
  EXPECT_TRUE(plain.converged);
  EXPECT_TRUE(given.converged);
  EXPECT_EQ(given.iterations, plain.iterations);
  EXPECT_EQ(products, plain_products - 1);
  EXPECT_LT((x_given - x_plain).norm(), 1e-12 * x_plain.norm());
  EXPECT_LT((sys.dense * x_given - b).norm(), 1e-11 * b.norm());
}

TEST(PcgSolverTest, EveryPreconditionerApplicationIsUsedByAnIteration) {
  // One application before the first iteration and one after each iteration that goes on: a solve
  // stopped by the tolerance or by the cap applies it exactly `iterations` times (the shipped
  // preconditioner costs as much as an iteration's product: one for nothing is ~0.5 ms a step).
  const SmallSystem sys = MakeSystem();
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(sys.model.pattern, sys.values);
  const Eigen::VectorXd b = TestVector(sys.model.num_dofs());
  int applications = 0;
  const MatrixOperator apply = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    SymmetricPatternMultiply(sys.model.pattern, sys.values, in, out);
  };
  const Preconditioner pre = [&](const Eigen::VectorXd& res, Eigen::VectorXd& z) {
    ++applications;
    jacobi.Apply(res, z);
  };
  Eigen::VectorXd x_capped;
  const PcgResult capped = SolvePcg(apply, b, x_capped, pre, 1e-12, 3);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.iterations, 3);
  EXPECT_EQ(applications, 3);
  applications = 0;
  Eigen::VectorXd x_converged;
  const PcgResult converged = SolvePcg(apply, b, x_converged, pre, 1e-12, 1000);
  EXPECT_TRUE(converged.converged);
  EXPECT_GT(converged.iterations, 3);
  EXPECT_EQ(applications, converged.iterations);
}

TEST(PcgSolverTest, OverflowingOrIndefiniteInputIsABreakdownNotAConvergedSolve) {
  const SmallSystem sys = MakeSystem();
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(sys.model.pattern, sys.values);
  const Preconditioner pre = [&](const Eigen::VectorXd& res, Eigen::VectorXd& z) { jacobi.Apply(res, z); };
  const MatrixOperator apply = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    SymmetricPatternMultiply(sys.model.pattern, sys.values, in, out);
  };
  // |b| overflows although every entry is finite: a target of tol |b| = inf would pass any x.
  const Eigen::VectorXd huge = Eigen::VectorXd::Constant(sys.model.num_dofs(), 1e200);
  Eigen::VectorXd x = Eigen::VectorXd::Ones(huge.size());
  const PcgResult overflow = SolvePcg(apply, huge, x, pre, 1e-8, 20);
  EXPECT_TRUE(overflow.breakdown);
  EXPECT_FALSE(overflow.converged);
  EXPECT_TRUE(std::isnan(overflow.relative_residual));
  EXPECT_EQ(overflow.iterations, 0);
  // A = -(SPD): p.A p < 0 on the first direction.
  const MatrixOperator negative = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    apply(in, out);
    out = -out;
  };
  const Eigen::VectorXd b = TestVector(sys.model.num_dofs());
  Eigen::VectorXd y;
  const PcgResult indefinite = SolvePcg(negative, b, y, pre, 1e-8, 20);
  EXPECT_TRUE(indefinite.breakdown);
  EXPECT_FALSE(indefinite.converged);
  EXPECT_EQ(indefinite.iterations, 0);
  // A tolerance below what doubles can reach: the recursive residual falls until p.A p underflows
  // to 0, which stops the solve with x as good as it gets; that is not a breakdown.
  Eigen::VectorXd w;
  const PcgResult underflow = SolvePcg(apply, b, w, pre, 1e-300, 100000);
  EXPECT_FALSE(underflow.breakdown);
  EXPECT_FALSE(underflow.converged);
  EXPECT_LT(underflow.iterations, 100000);  // stopped by the underflow, not the cap
  const Eigen::VectorXd exact = sys.dense.ldlt().solve(b);
  EXPECT_LT((w - exact).norm(), 1e-10 * exact.norm());
  // A sane solve is no breakdown.
  Eigen::VectorXd z;
  const PcgResult sane = SolvePcg(apply, b, z, pre, 1e-8, 1000);
  EXPECT_TRUE(sane.converged);
  EXPECT_FALSE(sane.breakdown);
}

}  // namespace
}  // namespace vesica::physics
