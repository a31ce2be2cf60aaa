#pragma once
// Pose of a laparoscopic instrument about its trocar's remote centre (4 DOF + jaw), and the
// geometry it implies. Plain math, shared by rendering and (later) the physics step.

#include <Eigen/Core>

namespace vesica::physics {

/// Yaw and pitch aim the shaft about the remote centre; roll turns it about its own axis;
/// insertion is the tip's depth past the remote centre (m). jaw_angle_rad 0 = closed.
struct InstrumentPose {
  double yaw_rad = 0;
  double pitch_rad = 0;
  double roll_rad = 0;
  double insertion_m = 0;
  double jaw_angle_rad = 0;
};

/// Unit shaft direction (into the patient) for a pose, relative to a reference direction:
/// yaw turns about world z (cranial), pitch tilts about the yawed horizontal axis.
Eigen::Vector3d ShaftDirection(const Eigen::Vector3d& reference_direction, const InstrumentPose& pose);

/// The pose whose shaft from `remote_centre` points at `target` with the tip at `insertion_m`,
/// taking reference_direction itself as yaw = pitch = 0.
InstrumentPose AimAt(const Eigen::Vector3d& remote_centre, const Eigen::Vector3d& target, double insertion_m,
                     const Eigen::Vector3d& reference_direction);

/// Tip position: remote centre + insertion along the shaft.
Eigen::Vector3d TipPosition(const Eigen::Vector3d& remote_centre, const Eigen::Vector3d& reference_direction,
                            const InstrumentPose& pose);

}  // namespace vesica::physics
