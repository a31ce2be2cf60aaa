#pragma once
// The haptic arms of an arm station while something else drives the instruments (a recorded
// session being watched): the link stays up and supervised, so the surgeon's view keeps showing
// each arm's state and a fault can be cleared, but the arms render no force and move nothing.

#include <Eigen/Core>
#include <array>
#include <functional>

#include "app/session/arm_input.h"
#include "device/haptic_device.h"

namespace vesica::app {

class ArmsStandingBy final : public HapticIo {
 public:
  /// `devices` as ArmInput takes them (null: no arm for that instrument); `servo` runs the
  /// bridge's cycle (ArmBridge::Tick) from the haptic thread. The devices must outlive this.
  ArmsStandingBy(std::array<device::HapticDevice*, 2> devices, std::function<void()> servo);

  void ServoTick() override;
  /// The arms do not drive: the instruments' points stay those of the physics.
  bool ToolPoint(int instrument, Eigen::Vector3d& p_W) override;
  /// Whatever the scene's force, the arm renders none (the hand is not in the scene).
  void SetForce(int instrument, const Eigen::Vector3d& f_W) override;

 private:
  std::array<device::HapticDevice*, 2> devices_;
  std::function<void()> servo_;
};

}  // namespace vesica::app
