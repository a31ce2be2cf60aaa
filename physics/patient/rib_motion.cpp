#include "physics/patient/rib_motion.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vesica::physics {

RibAmplitudes Table1Amplitudes(int rib_number) {
  // Seed Table 1 (alpha_max, beta_max in degrees), from Wilson et al. (2001).
  static constexpr RibAmplitudes kTable[] = {{14.3, 13.7}, {11.4, 13.3}, {10.7, 10.1}, {9.6, 8.9},
                                             {9.4, 6.9},   {7.9, 6.6},   {7.9, 6.2},   {6.0, 6.3}};
  if (rib_number < 1 || rib_number > 12) throw std::invalid_argument("rib number must be 1-12");
  if (rib_number == 1) return {0.0, 0.0};
  if (rib_number <= 9) return kTable[rib_number - 2];
  if (rib_number == 10) return kTable[7];
  return {kTable[7].alpha_max_deg, 0.0};
}

SpineAxis SpineAxisFromVoxels(std::span<const Eigen::Vector3d> spine_voxels_m, double voxel_volume_m3) {
  if (spine_voxels_m.empty())
    throw std::invalid_argument("the label map has no spine voxels (needed for the rib centres)");
  const InertiaAxes axes = ComputeInertiaAxes(spine_voxels_m, voxel_volume_m3);
  SpineAxis spine{axes.centroid_m, axes.principal_axes.col(0)};
  if (spine.direction.z() < 0.0) spine.direction = -spine.direction;
  return spine;
}

Eigen::Matrix3d Rodrigues(const Eigen::Vector3d& k, double angle_rad) {
  Eigen::Matrix3d cross;
  cross << 0.0, -k.z(), k.y(), k.z(), 0.0, -k.x(), -k.y(), k.x(), 0.0;
  return Eigen::Matrix3d::Identity() + std::sin(angle_rad) * cross + (1.0 - std::cos(angle_rad)) * cross * cross;
}

RibModel BuildRibModel(bool left, int number, std::span<const Eigen::Vector3d> rib_voxels_m, double voxel_volume_m3,
                       const SpineAxis& spine) {
  const std::string name = std::string(left ? "left" : "right") + " rib " + std::to_string(number);
  if (rib_voxels_m.size() < 3) throw std::invalid_argument(name + " has fewer than 3 voxels");
  RibModel rib;
  rib.left = left;
  rib.number = number;
  rib.amplitudes = Table1Amplitudes(number);
  rib.inertia = ComputeInertiaAxes(rib_voxels_m, voxel_volume_m3);
  const Eigen::Vector3d e0 = rib.inertia.principal_axes.col(0), e1 = rib.inertia.principal_axes.col(1);
  rib.plane_normal = rib.inertia.principal_axes.col(2);
  const double along = rib.plane_normal.dot(spine.direction);
  if (std::abs(along) < 1e-3) throw std::invalid_argument(name + ": its rib plane is parallel to the spine's axis");
  rib.centre_m =
      spine.point_m + spine.direction * (rib.plane_normal.dot(rib.inertia.centroid_m - spine.point_m) / along);
  // The bucket handle turns about the axis that runs front to back (spine to sternum).
  const bool e0_is_ap = std::abs(e0.y()) >= std::abs(e1.y());
  rib.bucket_axis = e0_is_ap ? e0 : e1;
  rib.pump_axis = e0_is_ap ? e1 : e0;
  const Eigen::Vector3d arm = rib.inertia.centroid_m - rib.centre_m;
  const auto lift = [&](const Eigen::Vector3d& axis) { return axis.cross(arm).z(); };
  if (lift(rib.bucket_axis) < 0.0) rib.bucket_axis = -rib.bucket_axis;
  if (lift(rib.pump_axis) < 0.0) rib.pump_axis = -rib.pump_axis;
  return rib;
}

RibPose PoseRib(const RibModel& rib, double unit_signal, double thoracic_scale) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  RibPose pose;
  pose.centre_m = rib.centre_m;
  pose.alpha_rad = rib.amplitudes.alpha_max_deg * kDeg * thoracic_scale * unit_signal;  // eq. 10
  pose.beta_rad = rib.amplitudes.beta_max_deg * kDeg * thoracic_scale * unit_signal;    // eq. 11
  pose.rotation = Rodrigues(rib.pump_axis, pose.beta_rad) * Rodrigues(rib.bucket_axis, pose.alpha_rad);
  return pose;
}

}  // namespace vesica::physics
