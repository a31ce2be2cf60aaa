#pragma once
// Shared scenes for the FEM tests: box meshes, clamped faces, consistent face loads.

#include <cmath>
#include <memory>

#include <Eigen/Geometry>
#include <vector>

#include "physics/fem/fem_model.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics::testing {

/// Nodes of a box mesh whose coordinate `axis` equals `value` (within 1e-12 of the box size).
inline std::vector<int> NodesOnPlane(const TetrahedralMesh& mesh, int axis, double value) {
  std::vector<int> nodes;
  for (int i = 0; i < mesh.num_vertices(); ++i)
    if (std::abs(mesh.vertices(i, axis) - value) < 1e-9) nodes.push_back(i);
  return nodes;
}

inline std::vector<DirichletNode> Clamp(const std::vector<int>& nodes) {
  std::vector<DirichletNode> fixed;
  for (int n : nodes) fixed.push_back({n, {true, true, true}});
  return fixed;
}

/// Consistent nodal forces (3n, N) of a uniform traction (Pa, world vector) on the boundary faces
/// lying in the plane coordinate[axis] = value: each face gives traction * area / 3 to its nodes.
inline Eigen::VectorXd PlaneTractionForces(const TetrahedralMesh& mesh, int axis, double value,
                                           const Eigen::Vector3d& traction_Pa) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_vertices());
  static const int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (const auto& face : kFaces) {
      int v[3];
      bool on_plane = true;
      for (int k = 0; k < 3; ++k) {
        v[k] = mesh.tets(t, face[k]);
        on_plane = on_plane && std::abs(mesh.vertices(v[k], axis) - value) < 1e-9;
      }
      if (!on_plane) continue;
      const Eigen::Vector3d a = mesh.vertices.row(v[0]), b = mesh.vertices.row(v[1]), c = mesh.vertices.row(v[2]);
      const double area = 0.5 * (b - a).cross(c - a).norm();
      for (int k = 0; k < 3; ++k) f.segment<3>(3 * v[k]) += traction_Pa * area / 3.0;
    }
  return f;
}

/// A gallbladder-like body as the benchmarks step it: corotational, gallbladder material
/// (2.3 kPa, nu 0.45, 1,000 kg/m^3), Newmark, Rayleigh damping 1 / 0.01; solver and the rest as given.
inline FemSettings GallbladderNewmarkSettings(LinearSolverKind solver) {
  FemSettings s;
  s.element_model = ElementModel::kCorotational;
  s.integrator = TimeIntegrator::kNewmark;
  s.material = {2300.0, 0.45, 1000.0};
  s.rayleigh_mass_per_s = 1.0;
  s.rayleigh_stiffness_s = 0.01;
  s.solver = solver;
  return s;
}

/// The cantilever: L = 10, b = h = 1, E = 1000, nu = 0.3, x = 0 clamped.
inline FemModel MakeCantilever(int cells_through_thickness, const FemSettings& base) {
  const int c = cells_through_thickness;
  const TetrahedralMesh mesh = MakeBoxTetMesh({10.0, 1.0, 1.0}, {10 * c, c, c});
  FemSettings s = base;
  s.material.youngs_modulus_Pa = 1000.0;
  s.material.poisson_ratio = 0.3;
  return BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0)));
}

/// Mean of component `axis` of u over the given nodes.
inline double MeanDisplacement(const Eigen::VectorXd& u, const std::vector<int>& nodes, int axis) {
  double sum = 0.0;
  for (int n : nodes) sum += u[3 * n + axis];
  return sum / static_cast<double>(nodes.size());
}

}  // namespace vesica::physics::testing
