#include "device/arm_actuation.h"

#include <cmath>

namespace vesica::device {

ArmActuation ArmActuation::Nominal() {
  ArmActuation a;
  a.yaw = {0.0302, 14.0, 3.0};
  a.pitch = {0.0302, 14.0, 3.0};
  a.insertion = {0.0276, 1.0 / 0.010, 5.0};
  a.max_tip_force_N = 6.0;
  return a;
}

std::string_view ArmActuation::FirstInvalidField() const {
  auto bad = [](double v) { return !(std::isfinite(v) && v > 0.0); };
  if (bad(yaw.torque_constant_Nm_per_A)) return "yaw.torque_constant_Nm_per_A";
  if (bad(yaw.transmission_ratio)) return "yaw.transmission_ratio";
  if (bad(yaw.max_current_A)) return "yaw.max_current_A";
  if (bad(pitch.torque_constant_Nm_per_A)) return "pitch.torque_constant_Nm_per_A";
  if (bad(pitch.transmission_ratio)) return "pitch.transmission_ratio";
  if (bad(pitch.max_current_A)) return "pitch.max_current_A";
  if (bad(insertion.torque_constant_Nm_per_A)) return "insertion.torque_constant_Nm_per_A";
  if (bad(insertion.transmission_ratio)) return "insertion.transmission_ratio";
  if (bad(insertion.max_current_A)) return "insertion.max_current_A";
  if (bad(max_tip_force_N)) return "max_tip_force_N";
  return {};
}

std::string_view ToString(ActuationLimit limit) {
  switch (limit) {
    case ActuationLimit::kNone: return "none";
    case ActuationLimit::kTipForce: return "tip force";
    case ActuationLimit::kYawCurrent: return "yaw current";
    case ActuationLimit::kPitchCurrent: return "pitch current";
    case ActuationLimit::kInsertionCurrent: return "insertion current";
  }
  return "unknown";
}

MotorCurrentCommand TipForceToMotorCurrents(const ArmJoints& q, const Eigen::Vector3d& f_Tip_T,
                                            const ArmActuation& actuation, const Eigen::Vector3d& feedforward_A) {
  MotorCurrentCommand cmd;
  if (!f_Tip_T.allFinite() || !feedforward_A.allFinite()) {
    cmd.scale = 0.0;
    return cmd;
  }
  const Eigen::Vector3d max_A(actuation.yaw.max_current_A, actuation.pitch.max_current_A,
                              actuation.insertion.max_current_A);
  const Eigen::Vector3d ff = feedforward_A.cwiseMax(-max_A).cwiseMin(max_A);
  const Eigen::Vector3d left_A = max_A - ff.cwiseAbs();
  const Eigen::Vector4d tau = JointEffortsFromTipForce(q, f_Tip_T);
  const Eigen::Vector3d amps(tau[0] / actuation.yaw.EffortPerAmp(),
                             tau[1] / actuation.pitch.EffortPerAmp(),
                             tau[3] / actuation.insertion.EffortPerAmp());

  // The smallest ratio limit / demand over all limits sets one common scale.
  double scale = 1.0;
  auto consider = [&](double demand, double limit, ActuationLimit which) {
    if (demand > limit && limit / demand < scale) {
      scale = limit / demand;
      cmd.active_limit = which;
    }
  };
  consider(f_Tip_T.norm(), actuation.max_tip_force_N, ActuationLimit::kTipForce);
  consider(std::abs(amps[0]), left_A[0], ActuationLimit::kYawCurrent);
  consider(std::abs(amps[1]), left_A[1], ActuationLimit::kPitchCurrent);
  consider(std::abs(amps[2]), left_A[2], ActuationLimit::kInsertionCurrent);

  cmd.scale = scale;
  cmd.feedforward_A = ff;
  cmd.current_A = scale * amps + ff;
  cmd.joint_effort = scale * tau;
  cmd.f_rendered_T = scale * f_Tip_T;
  return cmd;
}

}  // namespace vesica::device
