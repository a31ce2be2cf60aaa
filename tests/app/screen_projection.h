#pragma once
// An independent pinhole model of the laparoscope (not VTK's): where a world point lands in the
// image, so image checks know which pixels an organ must cover.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "app/scenario/scenario.h"

namespace vesica::app::testing {

/// Pixel (column, row from the top) of world point p for the scenario's laparoscope camera with
/// cranial (z) up, vertical view angle, and the image's aspect ratio.
inline Eigen::Vector2d ProjectToPixel(const LaparoscopeConfig& scope, const Eigen::Vector3d& p, int width,
                                      int height) {
  const Eigen::Vector3d forward = (scope.look_at_m - scope.position_m).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const Eigen::Vector3d d = p - scope.position_m;
  const double t = std::tan(0.5 * scope.view_angle_deg * std::numbers::pi / 180.0);
  const double x_ndc = d.dot(right) / d.dot(forward) / (t * width / height);
  const double y_ndc = d.dot(up) / d.dot(forward) / t;
  return {0.5 * (x_ndc + 1.0) * width, 0.5 * (1.0 - y_ndc) * height};
}

}  // namespace vesica::app::testing
