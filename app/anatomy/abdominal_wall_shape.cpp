#include "app/anatomy/abdominal_wall_shape.h"

namespace vesica::app::anatomy {

double AbdominalWallField(const AbdominalWallShape& wall, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d q = (p_W - wall.centre_m).cwiseQuotient(wall.semi_axes_m);
  return 0.5 * wall.semi_axes_m.minCoeff() * (q.squaredNorm() - 1);
}

Box AbdominalWallBounds(const AbdominalWallShape& wall) {
  return {wall.centre_m - wall.semi_axes_m, wall.centre_m + wall.semi_axes_m};
}

}  // namespace vesica::app::anatomy
