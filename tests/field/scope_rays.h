#pragma once
// The ray through a pixel of the laparoscope's picture: the inverse of the independent pinhole
// model in tests/app/screen_projection.h (same eye, axes and view angle), so a test can cast its
// own rays at the organs instead of reading VTK's depth buffer.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "../app/screen_projection.h"
#include "app/scenario/scenario.h"

namespace vesica::app::testing {

struct ScopeRay {
  Eigen::Vector3d origin;     ///< the scope's tip
  Eigen::Vector3d direction;  ///< unit
};

/// The scope's tip: on its shaft, insertion_m in from the port (the angled optic, CameraOf).
inline Eigen::Vector3d ScopeEye(const LaparoscopeConfig& scope) { return CameraOf(scope).eye; }

/// The ray through the centre of pixel (col, row) of a width x height picture.
inline ScopeRay RayThroughPixel(const LaparoscopeConfig& scope, double col, double row, int width, int height) {
  const ScopeCamera c = CameraOf(scope);
  const double t = std::tan(0.5 * scope.view_angle_deg * std::numbers::pi / 180.0);
  const double x_ndc = 2.0 * (col + 0.5) / width - 1.0, y_ndc = 1.0 - 2.0 * (row + 0.5) / height;
  const Eigen::Vector3d d = c.forward + x_ndc * t * width / height * c.right + y_ndc * t * c.up;
  return {c.eye, d.normalized()};
}

}  // namespace vesica::app::testing
