#include "physics/fem/tet_element.h"

#include <Eigen/LU>

namespace vesica::physics {

TetElement MakeTetElement(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                          const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
  TetElement e;
  Eigen::Matrix3d dm;
  dm << x1 - x0, x2 - x0, x3 - x0;
  e.rest_volume_m3 = dm.determinant() / 6.0;
  e.rest_shape_inverse = dm.inverse();
  // Rows of Dm^-1 are grad N1..N3; N0 = 1 - N1 - N2 - N3.
  for (int a = 1; a < 4; ++a) e.shape_gradients[a] = e.rest_shape_inverse.row(a - 1).transpose();
  e.shape_gradients[0] = -(e.shape_gradients[1] + e.shape_gradients[2] + e.shape_gradients[3]);
  return e;
}

}  // namespace vesica::physics
