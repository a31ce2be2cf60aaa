#pragma once
// What one physics step tells the 1 kHz device loop about one instrument (docs/architecture.md: the
// haptic loop never waits for physics; between steps it renders force from the last contact
// frame and its contact-space compliance, as SOFA's LCP force feedback does). Plain data, so it
// crosses threads through a TripleBuffer.

#include <Eigen/Core>

namespace vesica::physics {

struct HapticContactFrame {
  bool active = false;     ///< some constraint row of this instrument carries force or is touching
  bool unilateral = true;  ///< contact (pushes only) rather than grasp (pulls too)
  double time_s = 0;       ///< simulation time of the step that produced it
  Eigen::Vector3d p_Tool_W = Eigen::Vector3d::Zero();  ///< tool point (tip / jaw) at the solve, m
  Eigen::Vector3d f_Tool_W = Eigen::Vector3d::Zero();  ///< force of the tissue on the tool there, N
  /// -d f_Tool / d p_Tool with the tissue as solved (contact-space compliance inverted), N/m.
  Eigen::Matrix3d stiffness_N_per_m = Eigen::Matrix3d::Zero();
  Eigen::Vector3d normal_W = Eigen::Vector3d::Zero();  ///< unilateral: tissue normal, force along +n
};

/// Force on the tool at its current point: the frame's force plus its stiffness times the tool's
/// displacement since the solve; a contact lets go (zero force) once the tool has backed out.
/// O(1), allocation-free: the device loop calls it every millisecond.
Eigen::Vector3d RenderContactForce(const HapticContactFrame& frame, const Eigen::Vector3d& p_Tool_W);

}  // namespace vesica::physics
