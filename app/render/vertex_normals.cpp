#include "app/render/vertex_normals.h"

#include <Eigen/Geometry>

namespace vesica::app {

physics::Vertices VertexNormals(const physics::Vertices& V, const physics::Triangles& F) {
  physics::Vertices N = physics::Vertices::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();  // length = 2 * area: area weighting
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double len = N.row(v).norm();
    if (len > 0)
      N.row(v) /= len;
    else
      N.row(v) = Eigen::RowVector3d::UnitZ();
  }
  return N;
}

}  // namespace vesica::app
