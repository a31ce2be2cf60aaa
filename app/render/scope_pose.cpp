#include "app/render/scope_pose.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vesica::app {

namespace {

// Unit image "up" for a line of sight: the anterior wall (+y), or cranial (+z) when the line of
// sight runs along y.
Eigen::Vector3d HorizonUp(const Eigen::Vector3d& forward) {
  Eigen::Vector3d up = Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY().dot(forward) * forward;
  if (up.norm() < 1e-3) up = Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(forward) * forward;
  return up.normalized();
}

}  // namespace

ScopePose ScopePoseOf(const LaparoscopeConfig& scope) {
  const Eigen::Vector3d line = scope.look_at_m - scope.position_m;
  const double distance_m = line.norm();
  if (!(scope.insertion_m < distance_m))
    throw std::invalid_argument("laparoscope: insertion_m " + std::to_string(scope.insertion_m) +
                                " m does not leave look_at_m in front of the tip (" + std::to_string(distance_m) +
                                " m from the port)");
  if (!(std::abs(scope.scope_angle_deg) < 90.0))
    throw std::invalid_argument("laparoscope: scope_angle_deg " + std::to_string(scope.scope_angle_deg) +
                                " is outside (-90, 90)");
  const Eigen::Vector3d along = line / distance_m;
  // In the triangle port P, tip T, look_at L: |PT| = insertion, |PL| = distance, and the sight
  // line T->L turns off the shaft P->T by the scope's angle, so the angle at T is 180 - angle.
  // The law of sines gives the angle at L; the shaft leaves P at the rest of the scope's angle
  // from P->L, tilted toward the image's up (the view then looks down onto the field).
  const double angle_rad = scope.scope_angle_deg * std::numbers::pi / 180.0;
  const double at_look_at_rad = std::asin(scope.insertion_m * std::sin(angle_rad) / distance_m);
  const double shaft_tilt_rad = angle_rad - at_look_at_rad;
  const Eigen::Vector3d tilt_toward = HorizonUp(along);
  ScopePose pose;
  pose.shaft_W = std::cos(shaft_tilt_rad) * along + std::sin(shaft_tilt_rad) * tilt_toward;
  // The shaft turned a right angle toward the wall in the same plane: the optic looks the scope's
  // angle from the shaft away from it, down onto look_at (for 0 degrees exactly the shaft).
  const Eigen::Vector3d shaft_normal = std::cos(shaft_tilt_rad) * tilt_toward - std::sin(shaft_tilt_rad) * along;
  pose.forward_W = std::cos(angle_rad) * pose.shaft_W - std::sin(angle_rad) * shaft_normal;
  pose.eye_W = scope.position_m + scope.insertion_m * pose.shaft_W;
  pose.up_W = HorizonUp(pose.forward_W);
  return pose;
}

}  // namespace vesica::app
