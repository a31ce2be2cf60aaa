#pragma once
// Rib kinematics (seed section 4.3): each rib turns rigidly about a centre on the spine's axis, by
// the bucket-handle angle alpha(t) = alpha_max M(t) about one axis of its rib plane and the
// pump-handle angle beta(t) = beta_max M(t) about the other (eqs. 10-11), by Rodrigues' formula.
// Axes and centre come from the voxels (eq. 9); amplitudes from Table 1 (Wilson et al., 2001).

#include <Eigen/Core>
#include <span>

#include "physics/patient/inertia_matrix.h"

namespace vesica::physics {

/// Table 1 (degrees) for ribs 2-9. Ribs outside the table: rib 1 stays still (it is held by the
/// manubrium and the scalenes and Table 1 gives it nothing); ribs 10-12 take rib 9's bucket-handle
/// amplitude, the lowest measured; rib 10 also its pump handle (its cartilage joins rib 9's), the
/// floating ribs 11-12 none (no anterior attachment to lever).
struct RibAmplitudes {
  double alpha_max_deg = 0.0;  ///< bucket handle
  double beta_max_deg = 0.0;   ///< pump handle
};
[[nodiscard]] RibAmplitudes Table1Amplitudes(int rib_number);

/// The spine's axial line: through the spine's centroid along its largest-spread principal axis.
struct SpineAxis {
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit, pointing cranially (z >= 0)
};
[[nodiscard]] SpineAxis SpineAxisFromVoxels(std::span<const Eigen::Vector3d> spine_voxels_m, double voxel_volume_m3);

struct RibModel {
  bool left = false;
  int number = 0;  ///< 1-12
  InertiaAxes inertia;
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();  ///< rib plane: principal axes 0 and 1
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();       ///< where the spine's axis meets the rib plane
  Eigen::Vector3d bucket_axis = Eigen::Vector3d::UnitY();   ///< in-plane axis nearer antero-posterior
  Eigen::Vector3d pump_axis = Eigen::Vector3d::UnitX();     ///< the other in-plane axis
  RibAmplitudes amplitudes;
};

/// Builds one rib's model from its bone voxels. Both axes are signed so that a positive angle
/// lifts the rib's centroid (inspiration). Throws std::invalid_argument (naming the rib) when the
/// rib plane is parallel to the spine's axis.
[[nodiscard]] RibModel BuildRibModel(bool left, int number, std::span<const Eigen::Vector3d> rib_voxels_m,
                                     double voxel_volume_m3, const SpineAxis& spine);

/// Rodrigues' rotation matrix about a unit axis.
[[nodiscard]] Eigen::Matrix3d Rodrigues(const Eigen::Vector3d& unit_axis, double angle_rad);

/// A rib's rigid motion for the signal value m = M(t)/A in [-1, 1]: p -> centre + R (p - centre).
struct RibPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  double alpha_rad = 0.0;
  double beta_rad = 0.0;
  [[nodiscard]] Eigen::Vector3d Apply(const Eigen::Vector3d& p) const { return centre_m + rotation * (p - centre_m); }
};
[[nodiscard]] RibPose PoseRib(const RibModel& rib, double unit_signal, double thoracic_scale);

}  // namespace vesica::physics
