#pragma once
// An independent pinhole model of the laparoscope (not VTK's): where a world point lands in the
// image, so image checks know which pixels an organ must cover.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "app/scenario/scenario.h"

namespace vesica::app::testing {

/// Pixel (column, row from the top) of world point p for the scenario's laparoscope: the camera
/// at the scope's tip (insertion_m in from the port toward look_at), the anterior wall (+y) up,
/// vertical view angle, the image's aspect ratio. The patient frame (x left, y anterior, z
/// cranial) is left-handed, so seen from the feet the patient's left (+x) is on the image's right
/// when looking cranially: image right = up x forward here, not forward x up.
inline Eigen::Vector2d ProjectToPixel(const LaparoscopeConfig& scope, const Eigen::Vector3d& p, int width,
                                      int height) {
  const Eigen::Vector3d forward = (scope.look_at_m - scope.position_m).normalized();
  const Eigen::Vector3d eye = scope.position_m + scope.insertion_m * forward;
  const Eigen::Vector3d up = (Eigen::Vector3d::UnitY() - forward.y() * forward).normalized();
  const Eigen::Vector3d right = up.cross(forward);
  const Eigen::Vector3d d = p - eye;
  const double t = std::tan(0.5 * scope.view_angle_deg * std::numbers::pi / 180.0);
  const double x_ndc = d.dot(right) / d.dot(forward) / (t * width / height);
  const double y_ndc = d.dot(up) / d.dot(forward) / t;
  return {0.5 * (x_ndc + 1.0) * width, 0.5 * (1.0 - y_ndc) * height};
}

}  // namespace vesica::app::testing
