// The corotational tangent assembled node pair by node pair (tangent_blocks.h) by the SIMD pass:
// the pairs cover the pattern once, and the assembled values are the analytic tangents of a body
// at rest (the linear stiffness) and of a rigidly turned one (R K R^T), whatever the output held.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <limits>

#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_model.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// A box with one extra vertex in no tet (held: a free one would have no mass and no stiffness): its
// diagonal block is in the pattern with no tet behind it.
TetrahedralMesh BoxWithIsolatedVertex() {
  TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 3});
  const Eigen::Index n = mesh.vertices.rows();
  mesh.vertices.conservativeResize(n + 1, 3);
  mesh.vertices.row(n) << 0.2, 0.2, 0.2;
  return mesh;
}

FemModel Model(const TetrahedralMesh& mesh, ElementKernel kernel) {
  FemSettings s;
  s.material = {2300.0, 0.45, 1000.0};
  s.element_model = ElementModel::kCorotational;
  s.element_kernel = kernel;
  return BuildFemModel(mesh, s, {{mesh.num_vertices() - 1, {true, true, true}}});
}

std::vector<ElementKernel> SimdKernelsOfThisCpu() {
  std::vector<ElementKernel> kernels;
  for (ElementKernel k : {ElementKernel::kAvx2, ElementKernel::kAvx512})
    if (ResolveElementKernel(k) == k) kernels.push_back(k);
  return kernels;
}

TEST(TangentBlocksTest, OnePairPerBlockAndItsTransposeTenCornerPairsPerTet) {
  const TetrahedralMesh mesh = BoxWithIsolatedVertex();
  const FemModel m = Model(mesh, ElementKernel::kAuto);
  const TangentBlocks& b = m.tangent_blocks;
  const Eigen::Index nodes = mesh.num_vertices();
  const long blocks = m.pattern.structure.nonZeros() / 9;  // diagonal blocks + 2 per neighbour pair
  EXPECT_EQ(b.num_pairs(), (blocks + nodes) / 2);
  EXPECT_EQ(b.pair_begin.back(), 10 * mesh.num_tets());  // 4 diagonal + 6 edge pairs a tet
  int diagonal = 0, empty = 0;
  for (int p = 0; p < b.num_pairs(); ++p) {
    if (p > 0) {
      EXPECT_LT(b.slot_ab[p - 1], b.slot_ab[p]);  // column by column, each block once
    }
    diagonal += b.slot_ab[p] == b.slot_ba[p];
    if (b.pair_begin[p] == b.pair_begin[p + 1]) {
      ++empty;
      EXPECT_EQ(b.slot_ab[p], m.pattern.diagonal_slot[3 * (nodes - 1)]);
      EXPECT_EQ(b.shear_diagonal[p], 0.0);
    }
  }
  EXPECT_EQ(diagonal, nodes);
  EXPECT_EQ(empty, 1);  // the isolated vertex
}

// At rest every element's R is I: the tangent is the linear stiffness. Turned rigidly by R, every
// element's R is R: the tangent is R K R^T block by block. The output starts as NaN: every value of
// the pattern must be written.
TEST(TangentBlocksTest, AssembledTangentIsTheLinearStiffnessAtRestAndTurnsWithARigidTurn) {
  const auto kernels = SimdKernelsOfThisCpu();
  if (kernels.empty()) GTEST_SKIP() << "no AVX2/AVX-512 on this CPU: the pair assembly does not run";
  const TetrahedralMesh mesh = BoxWithIsolatedVertex();
  const Eigen::Index n = mesh.num_vertices();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.4, -1.0, 2.0).normalized()).toRotationMatrix();
  for (ElementKernel kernel : kernels) {
    const FemModel m = Model(mesh, kernel);
    const Eigen::MatrixXd k0 = PatternMatrix(m.pattern, m.linear_stiffness_values).toDense();
    const double scale = k0.cwiseAbs().maxCoeff();
    Eigen::MatrixXd turn = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    Eigen::VectorXd u_turned(3 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
      turn.block<3, 3>(3 * i, 3 * i) = r;
      const Eigen::Vector3d x = mesh.vertices.row(i);
      u_turned.segment<3>(3 * i) = r * x - x;
    }
    const Eigen::MatrixXd expected_turned = turn * k0 * turn.transpose();
    struct Case {
      Eigen::VectorXd u;
      const Eigen::MatrixXd* expected;
    };
    for (const Case& c : {Case{Eigen::VectorXd::Zero(3 * n), &k0}, Case{u_turned, &expected_turned}}) {
      std::vector<Eigen::Vector4d> cache;
      Eigen::VectorXd force;
      Eigen::VectorXd tangent =
          Eigen::VectorXd::Constant(m.pattern.structure.nonZeros(), std::numeric_limits<double>::quiet_NaN());
      for (int call = 0; call < 2; ++call) ComputeElasticForces(m, c.u, &tangent, &force, &cache);  // cold, warm
      ASSERT_TRUE(tangent.allFinite()) << "a value of the pattern was not written";
      const Eigen::MatrixXd k = PatternMatrix(m.pattern, tangent).toDense();
      EXPECT_LT((k - *c.expected).cwiseAbs().maxCoeff(), 1e-12 * scale);
      const Eigen::Matrix3d isolated = k.block(3 * (n - 1), 3 * (n - 1), 3, 3);
      EXPECT_TRUE(isolated.isZero(0.0));  // the vertex in no tet
    }
  }
}

// Only bodies that assemble their tangent get the pair lists; a matrix-free one (the SOFA beam's
// solver) never assembles it, and a tangent asked of it anyway is still right (the scalar pass).
TEST(TangentBlocksTest, BuiltOnlyForBodiesThatAssembleTheTangent) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2});
  FemSettings s;
  s.material = {2300.0, 0.45, 1000.0};
  s.element_model = ElementModel::kCorotational;
  s.solver = LinearSolverKind::kRotatedFactorPcg;
  ASSERT_TRUE(TangentIsMatrixFree(s));
  const FemModel matrix_free = BuildFemModel(mesh, s, {});
  EXPECT_EQ(matrix_free.tangent_blocks.num_pairs(), 0);
  s.rotated_factor_gauss_seidel = true;
  ASSERT_FALSE(TangentIsMatrixFree(s));
  const FemModel assembled = BuildFemModel(mesh, s, {});
  EXPECT_EQ(assembled.tangent_blocks.num_pairs(),
            (assembled.pattern.structure.nonZeros() / 9 + mesh.num_vertices()) / 2);
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(3 * mesh.num_vertices(), 0.0, 0.002);
  Eigen::VectorXd k_free, k_assembled, f;
  std::vector<Eigen::Vector4d> cache_free, cache_assembled;
  ComputeElasticForces(matrix_free, u, &k_free, &f, &cache_free);
  ComputeElasticForces(assembled, u, &k_assembled, &f, &cache_assembled);
  EXPECT_LT((k_free - k_assembled).norm(), 1e-12 * k_assembled.norm());
}

}  // namespace
}  // namespace vesica::physics
