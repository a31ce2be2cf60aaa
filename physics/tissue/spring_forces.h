#pragma once

#include <Eigen/Core>
#include <vector>

#include "physics/tissue/connective_tissue.h"

namespace vesica::physics {

struct SpringMaterial {
  double stiffness = 50.0;  ///< N/m, >= 0
  double damping = 0.05;    ///< N s/m, >= 0, acts along the spring only
};

/// Force on the gallbladder end of one spring, with d = x_liver - x_gb and v = v_liver - v_gb:
/// f = k (|d| - L0) d/|d| + c (v . d/|d|) d/|d|. The liver end gets -f. Zero when |d| = 0.
Eigen::Vector3d SpringForceOnGallbladder(const Eigen::Vector3d& x_gallbladder, const Eigen::Vector3d& x_liver,
                                         const Eigen::Vector3d& v_gallbladder, const Eigen::Vector3d& v_liver,
                                         double rest_length, const SpringMaterial& material);

/// Nodal forces of all alive springs: barycentric transpose onto the FEM gallbladder nodes
/// (#GB.V by 3) and onto the liver surface vertices (#L.V by 3). Momentum is conserved.
struct LiverPointForce {
  int triangle = -1;                                  ///< liver surface triangle
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  ///< barycentric point on it
  Eigen::Vector3d force = Eigen::Vector3d::Zero();    ///< N, on the liver
};
struct TissueNodalForces {
  Vertices gallbladder;                       ///< N, per FEM node
  Vertices liver;                             ///< N, per liver surface vertex
  std::vector<LiverPointForce> liver_points;  ///< N, one per alive spring, for BEM tractions
};
TissueNodalForces ComputeTissueForces(const ConnectiveTissue& tissue, const TetrahedralMesh& gallbladder,
                                      const Vertices& gallbladder_velocities, const TriangleMesh& liver,
                                      const Vertices& liver_velocities, const SpringMaterial& material);

}  // namespace vesica::physics
