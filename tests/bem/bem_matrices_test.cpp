#include "physics/bem/bem_matrices.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <Eigen/Eigenvalues>

#include "physics/bem/ellipsoid_surface.h"
#include "physics/mesh/mesh_validation.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

const ElasticMaterial kLiver = LiverMaterial();

// A rigid translation produces no traction: H u = 0 row by row (the diagonal blocks come from
// this identity, so this checks the assembly bookkeeping for every row and component).
TEST(BemMatricesTest, RigidTranslationIsInTheNullSpaceOfH) {
  const TriangleMesh mesh = MakeEllipsoidSurface({0.1, 0.07, 0.04}, 120);
  const BemMatrices m = AssembleBemMatrices(mesh, kLiver);
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(m.H.cols());
    for (int i = 0; i < mesh.num_vertices(); ++i) u(3 * i + k) = 1.0;
    const Eigen::VectorXd hu = m.H * u;
    const double scale = m.H.cwiseAbs().rowwise().sum().maxCoeff();
    for (Eigen::Index row = 0; row < hu.size(); ++row) EXPECT_NEAR(hu(row), 0.0, 1e-13 * scale) << row;
  }
}

TEST(BemMatricesTest, GIsPositiveOnTheDiagonalAndFinite) {
  const TriangleMesh mesh = MakeIcosphere(0.05, 1);
  const BemMatrices m = AssembleBemMatrices(mesh, kLiver);
  EXPECT_TRUE(m.H.allFinite());
  EXPECT_TRUE(m.G.allFinite());
  // U* is positive definite, so each node's self-influence G_ii is too.
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Matrix3d gii = m.G.block<3, 3>(3 * i, 3 * i);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(0.5 * (gii + gii.transpose())).eigenvalues().minCoeff(), 0.0);
  }
}

// Exact linear field u = F x (strain sym F, rotation skew F) with traction t = sigma n at the
// exact sphere normal. The residual |H u - G t| / |G t| is the discretisation error (flat
// triangles, linear interpolation), falling as the mesh is refined.
TEST(BemMatricesTest, LinearFieldResidualFallsUnderRefinement) {
  Eigen::Matrix3d F;
  F << 1.0e-3, 0.4e-3, -0.2e-3,  //
      -0.1e-3, -0.5e-3, 0.3e-3,  //
      0.6e-3, 0.2e-3, 0.8e-3;
  const Eigen::Matrix3d strain = 0.5 * (F + F.transpose());
  const double nu = kLiver.poisson_ratio, mu = LameMu(kLiver);
  const double lambda = 2 * mu * nu / (1 - 2 * nu);
  const Eigen::Matrix3d stress = lambda * strain.trace() * Eigen::Matrix3d::Identity() + 2 * mu * strain;
  std::vector<double> residual;
  for (int level = 1; level <= 3; ++level) {
    const TriangleMesh mesh = MakeIcosphere(0.05, level);
    const BemMatrices m = AssembleBemMatrices(mesh, kLiver);
    Eigen::VectorXd u(m.H.cols()), t(m.H.cols());
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      const Eigen::Vector3d x = mesh.vertices.row(i).transpose();
      u.segment<3>(3 * i) = F * x;
      t.segment<3>(3 * i) = stress * x.normalized();
    }
    residual.push_back((m.H * u - m.G * t).norm() / (m.G * t).norm());
  }
  for (std::size_t k = 1; k < residual.size(); ++k) {
    const double rate = std::log2(residual[k - 1] / residual[k]);
    std::cout << "linear-field residual " << residual[k - 1] << " -> " << residual[k]
              << ", rate h^" << rate << "\n";
    EXPECT_GT(rate, 1.5) << "residual must fall at least like h^1.5 (h halves per level)";
  }
  EXPECT_LT(residual.back(), 0.02);
}

TEST(BemMatricesTest, RejectsOpenSurfaceAndBadMaterial) {
  TriangleMesh open = MakeIcosphere(0.05, 1);
  open.triangles.conservativeResize(open.num_triangles() - 1, 3);
  EXPECT_THROW(AssembleBemMatrices(open, kLiver), MeshError);
  EXPECT_THROW(AssembleBemMatrices(MakeIcosphere(0.05, 1), ElasticMaterial{170e3, 0.5, 1060.0}), std::runtime_error);
}

}  // namespace
}  // namespace vesica::physics
