#include "physics/fem/elastic_forces.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "physics/fem/element_rotation.h"
#include "physics/fem/pcg_solver.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

FemModel Block(ElementModel model) {
  FemSettings s;
  s.element_model = model;
  s.material.youngs_modulus_Pa = 2300.0;
  s.material.poisson_ratio = 0.45;
  return BuildFemModel(MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3}), s, {});
}

// Displacement of a rigid rotation by `angle` about `axis` through point c.
Eigen::VectorXd RigidRotation(const FemModel& m, const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& c) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  Eigen::VectorXd u(m.num_dofs());
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d x = m.rest_mesh.vertices.row(i);
    u.segment<3>(3 * i) = r * (x - c) + c - x;
  }
  return u;
}

// Load scale: the nodal force of a 1% strain, E * strain * (element face area).
double LoadScale() { return 2300.0 * 0.01 * 0.01 * 0.01; }

TEST(ElasticForcesTest, CorotationalForcesVanishUnderRigidRotationWhereLinearOnesDoNot) {
  const FemModel corotational = Block(ElementModel::kCorotational);
  const FemModel linear = Block(ElementModel::kLinear);
  const Eigen::VectorXd u = RigidRotation(corotational, {1.0, 2.0, 0.5}, M_PI / 2.0, {0.01, 0.02, -0.03});
  Eigen::VectorXd f_corot, f_linear;
  const double e_corot = ComputeElasticForces(corotational, u, nullptr, &f_corot);
  const double e_linear = ComputeElasticForces(linear, u, nullptr, &f_linear);
  EXPECT_LT(f_corot.cwiseAbs().maxCoeff(), 1e-9 * LoadScale());
  EXPECT_LT(std::abs(e_corot), 1e-15);
  EXPECT_GT(f_linear.cwiseAbs().maxCoeff(), 10.0 * LoadScale());  // linear FEM sees a huge "strain"
  EXPECT_GT(e_linear, 0.0);
}

TEST(ElasticForcesTest, CorotationalMatchesLinearForSmallDisplacements) {
  const FemModel corotational = Block(ElementModel::kCorotational);
  const FemModel linear = Block(ElementModel::kLinear);
  Eigen::VectorXd u(corotational.num_dofs());
  for (int i = 0; i < corotational.num_nodes(); ++i) {
    const Eigen::Vector3d x = corotational.rest_mesh.vertices.row(i);
    u.segment<3>(3 * i) = 1e-7 * Eigen::Vector3d(std::sin(40 * x.x()), x.y() * x.z() * 100, std::cos(30 * x.z()));
  }
  Eigen::VectorXd f_corot, f_linear, k_corot;
  ComputeElasticForces(corotational, u, &k_corot, &f_corot);
  ComputeElasticForces(linear, u, nullptr, &f_linear);
  EXPECT_LT((f_corot - f_linear).norm(), 1e-5 * f_linear.norm());
  EXPECT_LT((k_corot - linear.linear_stiffness_values).cwiseAbs().maxCoeff(),
            1e-5 * linear.linear_stiffness_values.cwiseAbs().maxCoeff());
}

TEST(ElasticForcesTest, InternalForceIsTheEnergyGradient) {
  const FemModel m = Block(ElementModel::kCorotational);
  Eigen::VectorXd u = RigidRotation(m, {0, 1, 1}, 0.7, {0, 0, 0});
  for (int i = 0; i < m.num_nodes(); ++i) u[3 * i] += 0.1 * m.rest_mesh.vertices(i, 0);  // 10% stretch
  Eigen::VectorXd f;
  ComputeElasticForces(m, u, nullptr, &f);
  // Central differences of the energy along a few dofs.
  for (int dof : {5, 40, 101, 3 * m.num_nodes() - 1}) {
    const double h = 1e-7;
    Eigen::VectorXd up = u, um = u, dummy;
    up[dof] += h;
    um[dof] -= h;
    const double derivative =
        (ComputeElasticForces(m, up, nullptr, &dummy) - ComputeElasticForces(m, um, nullptr, &dummy)) / (2 * h);
    EXPECT_NEAR(f[dof], derivative, 1e-5 * f.cwiseAbs().maxCoeff()) << "dof " << dof;
  }
}

// The blocked product (one row index per 3x3 node block) is the sparse matrix times the vector.
TEST(ElasticForcesTest, PatternMultiplyEqualsTheSparseProduct) {
  const FemModel m = Block(ElementModel::kCorotational);
  Eigen::VectorXd values = m.linear_stiffness_values;
  for (Eigen::Index k = 0; k < values.size(); ++k) values[k] += 1e-3 * std::sin(0.1 * static_cast<double>(k));
  Eigen::VectorXd x(m.num_dofs());
  for (int i = 0; i < m.num_dofs(); ++i) x[i] = std::cos(0.7 * i);
  Eigen::VectorXd y;
  SymmetricPatternMultiply(m.pattern, values, x, y);
  // The gather form multiplies by the transpose: compare with A^T x.
  const Eigen::VectorXd expected = PatternMatrix(m.pattern, values).transpose() * x;
  EXPECT_LT((y - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
}

// A gallbladder-material box of `cells` whose element pass runs `kernel`.
FemModel GallbladderBlock(const Eigen::Vector3i& cells, ElementKernel kernel) {
  FemSettings s;
  s.material.youngs_modulus_Pa = 2300.0;
  s.material.poisson_ratio = 0.45;
  s.element_kernel = kernel;
  return BuildFemModel(MakeBoxTetMesh({0.08, 0.03, 0.03}, cells), s, {});
}

// A rigid turn of 1.1 rad with a stretch, a shear and a wave on top.
Eigen::VectorXd TurnedStretchedSheared(const FemModel& m) {
  Eigen::VectorXd u = RigidRotation(m, {1, 2, 0.5}, 1.1, {0, 0, 0});
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d x = m.rest_mesh.vertices.row(i);
    u.segment<3>(3 * i) += Eigen::Vector3d(0.1 * x.x(), 0.3 * x.x() * x.y() / 0.03, 0.05 * std::sin(90.0 * x.z()));
  }
  return u;
}

// Calls check(kernel, model, u) for every element kernel this CPU runs on two blocks of 252 and 270
// tets (whole and partial vectors of 4 and 8 lanes), u = TurnedStretchedSheared.
template <typename Check>
void ForEachKernelOnATurnedBlock(const Check& check) {
  for (ElementKernel kernel :
       {ElementKernel::kScalar, ElementKernel::kAvx2, ElementKernel::kAvx512, ElementKernel::kAuto})
    for (const Eigen::Vector3i& cells : {Eigen::Vector3i(7, 3, 2), Eigen::Vector3i(5, 3, 3)}) {
      if (kernel != ElementKernel::kAuto && ResolveElementKernel(kernel) != kernel) continue;
      const FemModel m = GallbladderBlock(cells, kernel);
      check(kernel, m, TurnedStretchedSheared(m));
    }
}

// The element-by-element product (CorotationalTangentTimes) is the assembled tangent's product, for
// the scalar and the SIMD kernels, on a turned, stretched and sheared body; the SIMD product gives
// it both from the rotation cache and from the turned gradients the pass left.
TEST(ElasticForcesTest, TangentTimesEqualsTheAssembledTangentProduct) {
  ForEachKernelOnATurnedBlock([](ElementKernel kernel, const FemModel& m, const Eigen::VectorXd& u) {
    std::vector<Eigen::Vector4d> cache;
    HugePageVector<double> turned;
    Eigen::VectorXd tangent, force;
    ComputeElasticForces(m, u, &tangent, &force, &cache, &turned);
    // Only the SIMD pass leaves them (kAuto is scalar too under VESICA_FEM_ELEMENT_KERNEL=scalar).
    EXPECT_EQ(turned.empty(), ResolveElementKernel(kernel) == ElementKernel::kScalar);
    Eigen::VectorXd x(m.num_dofs());
    for (int i = 0; i < m.num_dofs(); ++i) x[i] = std::cos(0.7 * i) * 1e-3;
    Eigen::VectorXd assembled, element_by_element, from_turned;
    SymmetricPatternMultiply(m.pattern, tangent, x, assembled);
    CorotationalTangentTimes(m, cache, x, element_by_element);
    CorotationalTangentTimes(m, cache, x, from_turned, &turned);
    const double scale = assembled.cwiseAbs().maxCoeff();
    EXPECT_LT((element_by_element - assembled).cwiseAbs().maxCoeff(), 1e-12 * scale)
        << "kernel " << static_cast<int>(kernel);
    EXPECT_LT((from_turned - assembled).cwiseAbs().maxCoeff(), 1e-12 * scale) << "kernel " << static_cast<int>(kernel);
    // Stale turned gradients (another displacement's) are used as given: the product follows them.
    if (!turned.empty()) {
      HugePageVector<double> other = turned;
      for (double& r : other) r *= 1.01;
      CorotationalTangentTimes(m, cache, x, from_turned, &other);
      EXPECT_GT((from_turned - assembled).cwiseAbs().maxCoeff(), 1e-3 * scale);
    }
  });
}

// Products taken in the element pass (PassProducts) are the separate products' values bit for bit,
// on every kernel (the scalar pass takes them after itself), for the double and the float-row
// tangent; the displacement leaves 94-130 of the tets with det F <= 0.2 (the scalar rule's lanes).
TEST(ElasticForcesTest, ProductsTakenInThePassAreTheSeparateProducts) {
  ForEachKernelOnATurnedBlock([](ElementKernel kernel, const FemModel& m, const Eigen::VectorXd& u) {
    Eigen::VectorXd x1(m.num_dofs()), x2(m.num_dofs());
    for (int i = 0; i < m.num_dofs(); ++i) x1[i] = std::cos(0.7 * i) * 1e-3, x2[i] = std::sin(1.3 * i) * 1e-2;
    for (bool float_tangent : {false, true}) {
      if (float_tangent && !FloatTangentAvailable(m)) continue;
      std::vector<Eigen::Vector4d> cache;
      HugePageVector<double> turned;
      Eigen::VectorXd tangent, force, y1, y2;
      PassProducts products;
      products.Add(x1, y1);
      products.Add(x2, y2);
      FloatBlockRows rows;
      rows.Reshape(m.pattern);
      const std::vector<int> offsets = FloatTangentRowOffsets(m.tangent_blocks, rows.ValueIndexOfSlots(m.pattern));
      if (float_tangent)
        ComputeElasticForcesFloatTangent(m, u, {rows.values(), &offsets}, 1.0, &force, &cache, &turned, nullptr,
                                         &products);
      else
        ComputeElasticForces(m, u, &tangent, &force, &cache, &turned, nullptr, 1.0, &products);
      Eigen::VectorXd separate1, separate2;
      CorotationalTangentTimes(m, cache, x1, separate1, &turned);
      CorotationalTangentTimes(m, cache, x2, separate2, &turned);
      ASSERT_EQ(y1.size(), m.num_dofs());
      EXPECT_GT(separate1.cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ((y1 - separate1).cwiseAbs().maxCoeff(), 0.0) << "kernel " << static_cast<int>(kernel);
      EXPECT_EQ((y2 - separate2).cwiseAbs().maxCoeff(), 0.0) << "kernel " << static_cast<int>(kernel);
    }
  });
}

TEST(ElasticForcesTest, ProductsInThePassNeedACorotationalBodyWithARotationCache) {
  const FemModel linear = Block(ElementModel::kLinear), corotational = Block(ElementModel::kCorotational);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(linear.num_dofs()), x = Eigen::VectorXd::Ones(linear.num_dofs());
  Eigen::VectorXd force, y;
  PassProducts products;
  products.Add(x, y);
  std::vector<Eigen::Vector4d> cache;
  EXPECT_THROW(ComputeElasticForces(linear, u, nullptr, &force, &cache, nullptr, nullptr, 1.0, &products),
               std::invalid_argument);
  EXPECT_THROW(ComputeElasticForces(corotational, u, nullptr, &force, nullptr, nullptr, nullptr, 1.0, &products),
               std::invalid_argument);
}

TEST(ElementRotationTest, RecoversRotationFromRotatedStretch) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
  const Eigen::Matrix3d stretch = Eigen::Vector3d(1.3, 0.8, 1.05).asDiagonal();
  EXPECT_LT((RotationFromDeformationGradient(r * stretch) - r).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ElementRotationTest, QuaternionIterationAgreesWithSvd) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(1.2, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::Matrix3d stretch;
  stretch << 1.2, 0.1, 0.0, 0.1, 0.9, 0.05, 0.0, 0.05, 1.1;  // symmetric positive definite
  const Eigen::Matrix3d f = r * stretch;
  Eigen::Vector4d q(0, 0, 0, 1);  // cold start from identity
  const Eigen::Matrix3d cold = RotationByQuaternionIteration(f, q, 100);
  EXPECT_LT((cold - RotationFromDeformationGradient(f)).cwiseAbs().maxCoeff(), 1e-9);
  // Warm start after a small further rotation converges within the body's 30-iteration cap.
  const Eigen::Matrix3d f2 = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitX()).toRotationMatrix() * f;
  EXPECT_LT((RotationByQuaternionIteration(f2, q, 30) - RotationFromDeformationGradient(f2)).cwiseAbs().maxCoeff(),
            1e-9);
}

// Newton's step on the polar condition converges quadratically: from the last step's rotation a
// stretched element's new rotation is exact to 1e-12 after 3 iterations (Mueller's fixed-length
// step needs ~20 at its linear rate of ~1/3).
TEST(ElementRotationTest, WarmStartedNewtonIterationConvergesInThreeSteps) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.8, Eigen::Vector3d(-1, 2, 0.5).normalized()).toRotationMatrix();
  Eigen::Matrix3d stretch;
  stretch << 1.3, 0.15, 0.0, 0.15, 0.75, 0.1, 0.0, 0.1, 1.05;  // 30% strains
  const Eigen::Matrix3d f = r * stretch;
  Eigen::Vector4d q(0, 0, 0, 1);
  RotationByQuaternionIteration(f, q, 100);
  const Eigen::Matrix3d f2 = Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix() * f;
  EXPECT_LT((RotationByQuaternionIteration(f2, q, 3) - RotationFromDeformationGradient(f2)).cwiseAbs().maxCoeff(),
            1e-12);
}

TEST(ElasticForcesTest, WarmStartedRotationsGiveTheSameForces) {
  const FemModel m = Block(ElementModel::kCorotational);
  std::vector<Eigen::Vector4d> cache;
  Eigen::VectorXd f_svd, f_cached, k_svd, k_cached;
  for (double angle : {0.3, 0.35, 0.4}) {  // a body turning and stretching over three calls
    Eigen::VectorXd u = RigidRotation(m, {0, 1, 1}, angle, {0, 0, 0});
    for (int i = 0; i < m.num_nodes(); ++i) u[3 * i] += 0.05 * m.rest_mesh.vertices(i, 0) * angle;
    const double e_svd = ComputeElasticForces(m, u, &k_svd, &f_svd);
    const double e_cached = ComputeElasticForces(m, u, &k_cached, &f_cached, &cache);
    EXPECT_NEAR(e_cached, e_svd, 1e-9 * e_svd);
    EXPECT_LT((f_cached - f_svd).cwiseAbs().maxCoeff(), 1e-8 * f_svd.cwiseAbs().maxCoeff());
    EXPECT_LT((k_cached - k_svd).cwiseAbs().maxCoeff(), 1e-8 * k_svd.cwiseAbs().maxCoeff());
  }
}

TEST(ElementRotationTest, InvertedElementStillGivesAProperRotation) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d inverted = r * Eigen::Vector3d(1.0, 1.0, -0.2).asDiagonal();
  const Eigen::Matrix3d q = RotationFromDeformationGradient(inverted);
  EXPECT_NEAR(q.determinant(), 1.0, 1e-12);
  EXPECT_LT((q.transpose() * q - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  // Flipping the smallest axis keeps the rotation of the undeformed part: q = r.
  EXPECT_LT((q - r).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::Matrix3d flat = r * Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
  EXPECT_NEAR(RotationFromDeformationGradient(flat).determinant(), 1.0, 1e-12);
}

}  // namespace
}  // namespace vesica::physics
