// Cross-check of the two elasticity models of the trainer on one liver-like body: the BEM on its
// surface and the project's tetrahedral FEM (physics/fem) in its volume, same material, same fixed
// region, same prescribed contact displacement. Their surface displacements must agree within 10%
// (relative L2 over the surface nodes, which both models share).

#include <gtest/gtest.h>

#include <iostream>

#include "physics/bem/capacitance_solver.h"
#include "physics/fem/fem_model.h"
#include "physics/fem/linear_statics.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// A tetrahedral ellipsoid: the Kuhn cube grid on [-1,1]^3 pushed radially onto the unit ball
// (p -> p |p|_inf / |p|_2, orientation-preserving), then scaled to the semi-axes.
TetrahedralMesh TetEllipsoid(const Eigen::Vector3d& semi_axes, int cells) {
  TetrahedralMesh mesh = MakeBoxTetMesh({2, 2, 2}, {cells, cells, cells});
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    Eigen::Vector3d p = mesh.vertices.row(i).transpose() - Eigen::Vector3d::Ones();
    if (p.norm() > 0) p *= p.cwiseAbs().maxCoeff() / p.norm();
    mesh.vertices.row(i) = p.cwiseProduct(semi_axes).transpose();
  }
  return mesh;
}

TEST(BemFemComparisonTest, SurfaceDisplacementsAgreeWithinTenPercent) {
  const Eigen::Vector3d axes(0.08, 0.06, 0.04);
  const TetrahedralMesh volume = TetEllipsoid(axes, 12);
  TetBoundary boundary = ExtractBoundary(volume);
  TriangleMesh& surface = boundary.surface;
  const ElasticMaterial liver = LiverMaterial();

  // Fixed cap at -x; a contact patch at the +x tip pulled out and sideways by a rigid u_c.
  const Eigen::RowVector3d u_c(4e-3, 0.0, 2e-3);
  surface.vertex_labels = Eigen::VectorXi::Zero(surface.num_vertices());
  std::vector<int> patch;
  for (int i = 0; i < surface.num_vertices(); ++i) {
    const double x = surface.vertices(i, 0) / axes.x();
    if (x < -0.6) surface.vertex_labels(i) = kLabelFixed;
    if (x > 0.85) patch.push_back(i);
  }
  ASSERT_GE(patch.size(), 5u);

  const BemModel bem = PrecomputeBemModel(surface, liver, "tet ellipsoid surface");
  BemCapacitanceSolver solver(bem);
  solver.SetContactNodes(patch);
  const Vertices prescribed = u_c.replicate(static_cast<Eigen::Index>(patch.size()), 1);
  BemSolution bem_solution;
  solver.Solve(prescribed, bem_solution);

  FemSettings settings;
  settings.body_name = "tet ellipsoid";
  settings.material = liver;
  settings.element_model = ElementModel::kLinear;
  std::vector<DirichletNode> dirichlet;
  Eigen::VectorXd prescribed_fem = Eigen::VectorXd::Zero(3 * volume.num_vertices());
  for (int i = 0; i < surface.num_vertices(); ++i)
    if (surface.vertex_labels(i) & kLabelFixed) dirichlet.push_back({boundary.surface_to_volume(i)});
  for (int i : patch) {
    dirichlet.push_back({boundary.surface_to_volume(i)});
    prescribed_fem.segment<3>(3 * boundary.surface_to_volume(i)) = u_c.transpose();
  }
  const FemModel fem = BuildFemModel(volume, settings, dirichlet);
  const Eigen::VectorXd u_fem = SolveLinearStatics(fem, Eigen::VectorXd::Zero(fem.num_dofs()), prescribed_fem);

  double diff_sq = 0, norm_sq = 0;
  for (int i = 0; i < surface.num_vertices(); ++i) {
    const Eigen::Vector3d fem_u = u_fem.segment<3>(3 * boundary.surface_to_volume(i));
    diff_sq += (bem_solution.displacement_m.row(i).transpose() - fem_u).squaredNorm();
    norm_sq += fem_u.squaredNorm();
  }
  const double relative_l2 = std::sqrt(diff_sq / norm_sq);
  std::cout << surface.num_vertices() << " surface nodes, " << volume.num_tets()
            << " tets: BEM vs FEM relative L2 " << relative_l2 << "\n";
  EXPECT_LT(relative_l2, 0.10);
}

}  // namespace
}  // namespace vesica::physics
