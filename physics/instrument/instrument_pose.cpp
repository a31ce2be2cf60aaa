#include "physics/instrument/instrument_pose.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace vesica::physics {

namespace {
// Spherical angles of a direction about the world z axis.
void Angles(const Eigen::Vector3d& d, double& azimuth, double& elevation) {
  azimuth = std::atan2(d.y(), d.x());
  elevation = std::asin(std::clamp(d.z() / d.norm(), -1.0, 1.0));
}
Eigen::Vector3d FromAngles(double azimuth, double elevation) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}
}  // namespace

Eigen::Vector3d ShaftDirection(const Eigen::Vector3d& reference_direction, const InstrumentPose& pose) {
  double az = 0, el = 0;
  Angles(reference_direction, az, el);
  return FromAngles(az + pose.yaw_rad, el + pose.pitch_rad);
}

InstrumentPose AimAt(const Eigen::Vector3d& remote_centre, const Eigen::Vector3d& target, double insertion_m,
                     const Eigen::Vector3d& reference_direction) {
  double az0 = 0, el0 = 0, az = 0, el = 0;
  Angles(reference_direction, az0, el0);
  Angles(target - remote_centre, az, el);
  InstrumentPose pose;
  pose.yaw_rad = std::remainder(az - az0, 2 * std::numbers::pi);
  pose.pitch_rad = el - el0;
  pose.insertion_m = insertion_m;
  return pose;
}

Eigen::Vector3d TipPosition(const Eigen::Vector3d& remote_centre, const Eigen::Vector3d& reference_direction,
                            const InstrumentPose& pose) {
  return remote_centre + pose.insertion_m * ShaftDirection(reference_direction, pose);
}

}  // namespace vesica::physics
