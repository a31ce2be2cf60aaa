#include "physics/scene/haptic_contact_frame.h"

namespace vesica::physics {

Eigen::Vector3d RenderContactForce(const HapticContactFrame& frame, const Eigen::Vector3d& p_Tool_W) {
  if (!frame.active) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d f = frame.f_Tool_W - frame.stiffness_N_per_m * (p_Tool_W - frame.p_Tool_W);
  // A contact only pushes: once the linear model's push turns into a pull, the tool has left.
  if (frame.unilateral && f.dot(frame.normal_W) <= 0.0) return Eigen::Vector3d::Zero();
  return f;
}

}  // namespace vesica::physics
