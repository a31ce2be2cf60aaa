#include "physics/bem/bem_matrices.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <Eigen/Eigenvalues>

#include "physics/bem/ellipsoid_surface.h"
#include "physics/bem/kelvin_solution.h"
#include "physics/bem/triangle_quadrature.h"
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

// The assembly's fused kernel against the reference Kelvin solutions (kelvin_solution.h): for a
// collocation node far from node j, the blocks H_ij and G_ij are plain quadratures of N_j T* and
// N_j U* over the triangles around j, recomputed here with 7 points on 16 sub-triangles each.
TEST(BemMatricesTest, FarBlocksMatchReferenceKelvinQuadrature) {
  const TriangleMesh mesh = MakeIcosphere(0.05, 2);
  const ElasticMaterial material = LiverMaterial();
  const BemMatrices m = AssembleBemMatrices(mesh, material);
  const int i = 0;
  const Eigen::Vector3d source = mesh.vertices.row(i).transpose();
  int checked = 0;
  for (int j = 1; j < mesh.num_vertices(); ++j) {
    if ((mesh.vertices.row(j).transpose() - source).norm() < 0.06) continue;  // far nodes only
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero(), g = Eigen::Matrix3d::Zero();
    for (int f = 0; f < mesh.num_triangles(); ++f) {
      int corner = -1;
      for (int c = 0; c < 3; ++c)
        if (mesh.triangles(f, c) == j) corner = c;
      if (corner < 0) continue;
      const Eigen::Vector3d n = TriangleNormal(mesh, f);
      const double area = TriangleArea(mesh, f);
      constexpr int kSplit = 4;  // 16 sub-triangles of a regular split in barycentric steps
      for (int a = 0; a < kSplit; ++a)
        for (int b = 0; a + b < kSplit; ++b)
          for (int flip = 0; flip < (a + b + 1 < kSplit ? 2 : 1); ++flip)
            for (const auto& q : TriangleGauss7()) {
              // Sub-triangle corners in (l1, l2) steps of 1/kSplit; flip = the inverted one.
              const double s1 = flip ? a + 1 - q.barycentric[1] : a + q.barycentric[1];
              const double s2 = flip ? b + 1 - q.barycentric[2] : b + q.barycentric[2];
              const double l1 = s1 / kSplit, l2 = s2 / kSplit, l0 = 1 - l1 - l2;
              const double bary[3] = {l0, l1, l2};
              Eigen::Vector3d x = Eigen::Vector3d::Zero();
              for (int c = 0; c < 3; ++c) x += bary[c] * mesh.vertices.row(mesh.triangles(f, c)).transpose();
              const double w = q.weight * area / (kSplit * kSplit) * bary[corner];
              h += w * KelvinTraction(x - source, n, material.poisson_ratio);
              g += w * KelvinDisplacement(x - source, LameMu(material), material.poisson_ratio);
            }
    }
    EXPECT_LT((m.H.block<3, 3>(3 * i, 3 * j) - h).norm(), 2e-3 * h.norm()) << "node " << j;
    EXPECT_LT((m.G.block<3, 3>(3 * i, 3 * j) - g).norm(), 2e-3 * g.norm()) << "node " << j;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(BemMatricesTest, RejectsOpenSurfaceAndBadMaterial) {
  TriangleMesh open = MakeIcosphere(0.05, 1);
  open.triangles.conservativeResize(open.num_triangles() - 1, 3);
  EXPECT_THROW(AssembleBemMatrices(open, kLiver), MeshError);
  EXPECT_THROW(AssembleBemMatrices(MakeIcosphere(0.05, 1), ElasticMaterial{170e3, 0.5, 1060.0}), std::runtime_error);
}

}  // namespace
}  // namespace vesica::physics
