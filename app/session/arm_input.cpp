#include "app/session/arm_input.h"

#include <Eigen/Geometry>
#include <utility>

namespace vesica::app {

Eigen::Matrix3d TrocarFrame(const physics::InstrumentMount& mount) {
  const Eigen::Vector3d z = mount.reference_direction_W.normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ());
  if (x.norm() < 1e-6) x = z.cross(Eigen::Vector3d::UnitX());
  x.normalize();
  Eigen::Matrix3d r;
  r << x, z.cross(x), z;
  return r;
}

ArmInput::ArmInput(std::array<device::HapticDevice*, 2> devices, std::array<physics::InstrumentMount, 2> mounts,
                   device::InputFrame fallback, std::function<void()> servo, ToolExchange right_port)
    : devices_(devices),
      mounts_(mounts),
      fallback_(fallback),
      servo_(std::move(servo)),
      right_port_(std::move(right_port)) {
  for (size_t i = 0; i < 2; ++i) R_WT_[i] = TrocarFrame(mounts_[i]);
}

device::InputFrame ArmInput::Sample(double time_s) {
  device::InputFrame f = fallback_;
  f.time_s = time_s;
  for (size_t i = 0; i < 2; ++i) {
    if (devices_[i] == nullptr) continue;
    const device::ToolState s = devices_[i]->GetToolState();
    const device::JointState q = devices_[i]->GetJointState();
    const Eigen::Vector3d tip_W = mounts_[i].p_RemoteCentre_W + R_WT_[i] * s.p_BTip_B;
    const double insertion = s.p_BTip_B.norm();
    physics::InstrumentPose pose = fallback_.instruments[i].pose;
    if (insertion > 1e-4)  // at the remote centre the shaft direction is undefined: keep the last one
      pose = physics::AimAt(mounts_[i].p_RemoteCentre_W, tip_W, insertion, mounts_[i].reference_direction_W);
    pose.insertion_m = insertion;
    pose.roll_rad = q.count > 2 ? q.position[2] : 0.0;
    pose.jaw_angle_rad = s.gripper_angle_rad;
    f.instruments[i].pose = pose;
    f.instruments[i].pedal = (s.buttons & 1u) != 0;
    if (i == device::kRight) {
      right_port_.OnButton((s.buttons & 2u) != 0);
      f.right_tool = right_port_.current();
    }
    fallback_.instruments[i] = f.instruments[i];
  }
  return f;
}

void ArmInput::ServoTick() {
  if (servo_) servo_();
}

bool ArmInput::ToolPoint(int instrument, Eigen::Vector3d& p_W) {
  const auto i = static_cast<size_t>(instrument);
  if (devices_.at(i) == nullptr) return false;
  p_W = mounts_[i].p_RemoteCentre_W + R_WT_[i] * devices_[i]->GetToolState().p_BTip_B;
  return true;
}

void ArmInput::SetForce(int instrument, const Eigen::Vector3d& f_W) {
  const auto i = static_cast<size_t>(instrument);
  if (devices_.at(i) != nullptr) devices_[i]->SetTipForce(R_WT_[i].transpose() * f_W);
}

}  // namespace vesica::app
