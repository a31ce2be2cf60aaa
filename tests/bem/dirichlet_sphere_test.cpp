// Dirichlet sphere: u = eps x on a sphere of radius a is a uniform dilation, whose exact surface
// traction is t = E eps / (1 - 2 nu) n. Solving G t = H u for t tests H, G and the singular
// quadrature together.

#include <gtest/gtest.h>

#include <iostream>

#include "physics/bem/bem_matrices.h"
#include "physics/bem/dense_lu_solve.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// Relative RMS error of the nodal traction against the exact one, for icosphere `level`.
double SphereTractionError(int level, double* max_error) {
  const ElasticMaterial material = LiverMaterial();
  const double radius = 0.05, eps = 0.01;
  const TriangleMesh mesh = MakeIcosphere(radius, level);
  BemMatrices m = AssembleBemMatrices(mesh, material);
  Eigen::VectorXd u(m.H.cols());
  for (int i = 0; i < mesh.num_vertices(); ++i) u.segment<3>(3 * i) = eps * mesh.vertices.row(i).transpose();
  Eigen::MatrixXd t = m.H * u;
  SolveDenseInPlace(m.G, t, "Dirichlet sphere");
  const double exact = material.youngs_modulus_Pa * eps / (1 - 2 * material.poisson_ratio);
  double sum_sq = 0, worst = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d expected = exact * mesh.vertices.row(i).transpose().normalized();
    const double e = (t.col(0).segment<3>(3 * i) - expected).norm() / exact;
    sum_sq += e * e;
    worst = std::max(worst, e);
  }
  *max_error = worst;
  return std::sqrt(sum_sq / mesh.num_vertices());
}

TEST(DirichletSphereTest, TractionWithinFivePercentAt642NodesAndFallsUnderRefinement) {
  double previous = 0;
  for (int level = 1; level <= 3; ++level) {
    double worst = 0;
    const double rms = SphereTractionError(level, &worst);
    std::cout << "icosphere level " << level << " (" << 10 * (1 << (2 * level)) + 2
              << " nodes): traction error rms " << rms << ", max " << worst << "\n";
    if (level > 1) {
      EXPECT_LT(rms, 0.5 * previous) << "error must fall under refinement";
    }
    if (level == 3) {
      EXPECT_LT(rms, 0.05);
      EXPECT_LT(worst, 0.05);
    }
    previous = rms;
  }
}

}  // namespace
}  // namespace vesica::physics
