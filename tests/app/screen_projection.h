#pragma once
// An independent pinhole model of the laparoscope (not VTK's, not app/render/scope_pose's): where
// a world point lands in the image, so image checks know which pixels an organ must cover.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "app/scenario/scenario.h"

namespace vesica::app::testing {

struct ScopeCamera {
  Eigen::Vector3d eye;      ///< the scope's tip
  Eigen::Vector3d forward;  ///< unit, toward look_at (the image's centre)
  Eigen::Vector3d up;       ///< unit, the anterior wall (+y) made orthogonal to forward
  Eigen::Vector3d right;    ///< unit, up x forward (the patient frame is left-handed)
};

/// The camera of an angled scope: the tip insertion_m along the shaft from the port, the shaft
/// tilted from the port->look_at line toward the anterior wall by whatever angle makes the line
/// from the tip to look_at leave the shaft at scope_angle_deg (found by bisection; the tilt is
/// between 0 and the scope's angle). A 0-degree scope looks along the port->look_at line.
inline ScopeCamera CameraOf(const LaparoscopeConfig& scope) {
  const Eigen::Vector3d along = (scope.look_at_m - scope.position_m).normalized();
  // A negative angle: the light post turned the other way, the shaft tilted away from the wall.
  const Eigen::Vector3d wall =
      std::copysign(1.0, scope.scope_angle_deg) * (Eigen::Vector3d::UnitY() - along.y() * along).normalized();
  const double angle = std::abs(scope.scope_angle_deg) * std::numbers::pi / 180.0;
  auto shaft_at = [&](double tilt) { return Eigen::Vector3d(std::cos(tilt) * along + std::sin(tilt) * wall); };
  auto sight_angle = [&](double tilt) {
    const Eigen::Vector3d shaft = shaft_at(tilt);
    const Eigen::Vector3d sight = scope.look_at_m - (scope.position_m + scope.insertion_m * shaft);
    return std::atan2(shaft.cross(sight).norm(), shaft.dot(sight));
  };
  double lo = 0, hi = angle;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (sight_angle(mid) < angle ? lo : hi) = mid;
  }
  ScopeCamera c;
  c.eye = scope.position_m + scope.insertion_m * (angle == 0 ? along : shaft_at(0.5 * (lo + hi)));
  c.forward = angle == 0 ? along : Eigen::Vector3d((scope.look_at_m - c.eye).normalized());
  c.up = (Eigen::Vector3d::UnitY() - c.forward.y() * c.forward).normalized();
  c.right = c.up.cross(c.forward);
  return c;
}

/// Pixel (column, row from the top) of world point p for the scenario's laparoscope: the camera
/// at the scope's tip (CameraOf), the anterior wall (+y) up, vertical view angle, the image's
/// aspect ratio. The patient frame (x left, y anterior, z cranial) is left-handed, so seen from
/// the feet the patient's left (+x) is on the image's right when looking cranially: image right =
/// up x forward here, not forward x up.
inline Eigen::Vector2d ProjectToPixel(const LaparoscopeConfig& scope, const Eigen::Vector3d& p, int width, int height) {
  const ScopeCamera c = CameraOf(scope);
  const Eigen::Vector3d d = p - c.eye;
  const double t = std::tan(0.5 * scope.view_angle_deg * std::numbers::pi / 180.0);
  const double x_ndc = d.dot(c.right) / d.dot(c.forward) / (t * width / height);
  const double y_ndc = d.dot(c.up) / d.dot(c.forward) / t;
  return {0.5 * (x_ndc + 1.0) * width, 0.5 * (1.0 - y_ndc) * height};
}

}  // namespace vesica::app::testing
