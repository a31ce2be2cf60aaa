#pragma once
// The ray through a pixel of the laparoscope's picture: the inverse of the independent pinhole
// model in tests/app/screen_projection.h (same eye, axes and view angle), so a test can cast its
// own rays at the organs instead of reading VTK's depth buffer.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "app/scenario/scenario.h"

namespace vesica::app::testing {

struct ScopeRay {
  Eigen::Vector3d origin;     ///< the scope's tip
  Eigen::Vector3d direction;  ///< unit
};

inline Eigen::Vector3d ScopeEye(const LaparoscopeConfig& scope) {
  const Eigen::Vector3d forward = (scope.look_at_m - scope.position_m).normalized();
  return scope.position_m + scope.insertion_m * forward;
}

/// The ray through the centre of pixel (col, row) of a width x height picture.
inline ScopeRay RayThroughPixel(const LaparoscopeConfig& scope, double col, double row, int width, int height) {
  const Eigen::Vector3d forward = (scope.look_at_m - scope.position_m).normalized();
  const Eigen::Vector3d up = (Eigen::Vector3d::UnitY() - forward.y() * forward).normalized();
  const Eigen::Vector3d right = up.cross(forward);
  const double t = std::tan(0.5 * scope.view_angle_deg * std::numbers::pi / 180.0);
  const double x_ndc = 2.0 * (col + 0.5) / width - 1.0, y_ndc = 1.0 - 2.0 * (row + 0.5) / height;
  const Eigen::Vector3d d = forward + x_ndc * t * width / height * right + y_ndc * t * up;
  return {ScopeEye(scope), d.normalized()};
}

}  // namespace vesica::app::testing
