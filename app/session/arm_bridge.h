#pragma once
// The CAN bridge to the scenario's haptic arms: for each instrument whose input is `can_arm`
// (SocketCAN interface, e.g. can0) or `emulated_arm` (vesica-armsim over UDP on loopback: the
// arm with node id n listens on port 20000 + 2(n-1) and sends to 20001 + 2(n-1), so
// `vesica-armsim --node-id 1` with its default ports is the left arm), a device::CanArm opened on
// its transport. Tick() runs every arm's servo cycle (the haptic loop calls it at 1 kHz).

#include <array>
#include <memory>
#include <string>

#include "app/scenario/scenario.h"
#include "device/can_arm.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::app {

class ArmBridge {
 public:
  /// Opens the transports of the scenario's arm instruments ([0] grasper, [1] hook; instruments
  /// without an arm stay null). Throws std::runtime_error naming the instrument and the
  /// interface or port when a transport cannot open. The arms then connect in the background.
  explicit ArmBridge(const Scenario& scenario);
  ~ArmBridge();

  static bool ScenarioUsesArms(const Scenario& scenario);
  std::array<device::HapticDevice*, 2> devices();
  void Tick();
  /// One line per arm: name, status, link losses (for the diagnostics overlay).
  std::string Describe() const;

 private:
  std::array<std::unique_ptr<fp::Transport>, 2> transports_;
  std::array<std::unique_ptr<device::CanArm>, 2> arms_;
  std::array<std::string, 2> names_;
};

}  // namespace vesica::app
