#pragma once
// Both instruments driven by haptic arms (device::HapticDevice: the CAN arm bridge to real
// hardware or to vesica-armsim): the arm's measured tip gives the instrument pose, the gripper
// the jaw, button 0 the pedal; the haptic loop reads the measured tip and sends the rendered
// force back. Each arm's base frame T has its origin at the trocar's remote centre and +z along
// the mount's reference direction (TrocarFrame), so positions and forces map with one rotation.

#include <Eigen/Core>
#include <array>
#include <functional>

#include "device/haptic_device.h"
#include "device/input/instrument_input_source.h"
#include "app/session/tool_exchange.h"
#include "physics/scene/dissection_settings.h"

namespace vesica::app {

/// R_WT: columns are the trocar frame's axes in world; z = the reference direction.
Eigen::Matrix3d TrocarFrame(const physics::InstrumentMount& mount);

/// What the haptic loop needs from real devices (SessionRunner's haptic thread calls it).
class HapticIo {
 public:
  virtual ~HapticIo() = default;
  /// Once per haptic tick, first: lets device bridges run their servo cycle.
  virtual void ServoTick() {}
  /// The tool point of instrument i in world (m), if the device measures it.
  virtual bool ToolPoint(int instrument, Eigen::Vector3d& p_W) = 0;
  /// The force (world, N) to render on instrument i's handle.
  virtual void SetForce(int instrument, const Eigen::Vector3d& f_W) = 0;
};

class ArmInput final : public device::InstrumentInputSource, public HapticIo {
 public:
  /// devices[i] drives instrument i (0 grasper, 1 hook); a null device leaves that instrument at
  /// `fallback` (e.g. the keyboard's pose). The devices must outlive this object. `servo` (may be
  /// empty) runs each device bridge's cycle (CanArm::Tick) from the haptic thread. `right_port`:
  /// the tools the right arm's handle button cycles through.
  ArmInput(std::array<device::HapticDevice*, 2> devices, std::array<physics::InstrumentMount, 2> mounts,
           device::InputFrame fallback = {}, std::function<void()> servo = {}, ToolExchange right_port = {});

  device::InputFrame Sample(double time_s) override;
  void ServoTick() override;
  bool ToolPoint(int instrument, Eigen::Vector3d& p_W) override;
  void SetForce(int instrument, const Eigen::Vector3d& f_W) override;

 private:
  std::array<device::HapticDevice*, 2> devices_;
  std::array<physics::InstrumentMount, 2> mounts_;
  std::array<Eigen::Matrix3d, 2> R_WT_;
  device::InputFrame fallback_;
  std::function<void()> servo_;
  ToolExchange right_port_;
};

}  // namespace vesica::app
