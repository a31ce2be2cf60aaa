#include "device/stylus/stylus_capabilities.h"

namespace vesica::device {

StylusCapabilities PhantomOmniCapabilities() {
  StylusCapabilities caps;
  caps.device.model_name = "Phantom Omni (Geomagic Touch)";
  caps.device.joint_count = 0;  // the pose is reported, not the six joint angles
  caps.device.position_dof = 3;
  caps.device.rotation_dof = 3;
  caps.device.force_dof = 3;
  caps.device.torque_dof = 0;
  caps.device.has_gripper = false;
  caps.device.button_count = 2;
  caps.device.max_force_N = 3.3;
  caps.device.max_stiffness_N_per_m = 1260.0;  // the Omni's x axis; y 2310, z 1020 (maker's sheet)
  caps.workspace_box_m = Eigen::Vector3d(0.160, 0.120, 0.070);
  caps.device.workspace_radius_m = 0.5 * caps.workspace_box_m.norm();
  caps.device.servo_rate_hz = 1000.0;
  caps.max_continuous_force_N = 0.88;
  return caps;
}

bool InsideWorkspace(const StylusCapabilities& caps, const Eigen::Vector3d& p_B) {
  return (p_B.cwiseAbs().array() <= 0.5 * caps.workspace_box_m.array()).all();
}

Eigen::Vector3d ClampToWorkspace(const StylusCapabilities& caps, const Eigen::Vector3d& p_B) {
  const Eigen::Vector3d half = 0.5 * caps.workspace_box_m;
  return p_B.cwiseMax(-half).cwiseMin(half);
}

}  // namespace vesica::device
