#include "physics/mesh/tetrahedral_mesh.h"

#include <Eigen/Geometry>

namespace vesica::physics {

double SignedTetVolume(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                       const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
  return (x1 - x0).dot((x2 - x0).cross(x3 - x0)) / 6.0;
}

double SignedTetVolume(const TetrahedralMesh& mesh, int t) {
  return SignedTetVolume(mesh.vertices.row(mesh.tets(t, 0)).transpose(),
                         mesh.vertices.row(mesh.tets(t, 1)).transpose(),
                         mesh.vertices.row(mesh.tets(t, 2)).transpose(),
                         mesh.vertices.row(mesh.tets(t, 3)).transpose());
}

double TotalVolume(const TetrahedralMesh& mesh) {
  double v = 0.0;
  for (int t = 0; t < mesh.num_tets(); ++t) v += SignedTetVolume(mesh, t);
  return v;
}

}  // namespace vesica::physics
