#include "device/arm_calibration.h"

#include <algorithm>
#include <cmath>

namespace vesica::device {

Eigen::Vector3d ArmCalibration::CompensationEffort(const ArmJoints& q, const Eigen::Vector4d& qd) const {
  const double v[3] = {qd[0], qd[1], qd[3]};
  Eigen::Vector3d tau;
  for (int j = 0; j < 3; ++j) {
    const double direction = std::clamp(v[j] / coulomb_fade_speed[j], -1.0, 1.0);
    tau[j] = coulomb[j] * direction + viscous[j] * v[j];
  }
  tau[1] += gravity_sin * std::sin(q.pitch_rad) + gravity_cos * std::cos(q.pitch_rad);
  return tau;
}

Eigen::Vector3d ArmCalibration::CompensationCurrent(const ArmJoints& q, const Eigen::Vector4d& qd) const {
  const Eigen::Vector3d tau = CompensationEffort(q, qd);
  return {tau[0] / effort_per_amp[0], tau[1] / effort_per_amp[1], tau[2] / effort_per_amp[2]};
}

ArmActuation ArmCalibration::Corrected(const ArmActuation& nominal) const {
  ArmActuation a = nominal;
  a.yaw.torque_constant_Nm_per_A *= torque_constant_correction[0];
  a.pitch.torque_constant_Nm_per_A *= torque_constant_correction[1];
  a.insertion.torque_constant_Nm_per_A *= torque_constant_correction[2];
  return a;
}

}  // namespace vesica::device
