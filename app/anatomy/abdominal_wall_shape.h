#pragma once
// The insufflated abdominal wall: the anterior half of an ellipsoid domed over the organs.

#include <Eigen/Core>

#include "app/anatomy/implicit_surface.h"

namespace vesica::app::anatomy {

struct AbdominalWallShape {
  Eigen::Vector3d centre_m{0.0, -0.04, 0.0};      ///< ellipsoid centre; metres
  Eigen::Vector3d semi_axes_m{0.20, 0.17, 0.26};  ///< x, y (dome height), z; metres
  double base_y_m = -0.04;                        ///< the dome keeps y above this (its open, posterior rim); metres
};

/// Ellipsoid field, scaled to about metres near the surface (negative inside).
double AbdominalWallField(const AbdominalWallShape& wall, const Eigen::Vector3d& p_W);

/// A box around the whole ellipsoid.
Box AbdominalWallBounds(const AbdominalWallShape& wall);

}  // namespace vesica::app::anatomy
