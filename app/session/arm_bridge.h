#pragma once
// The CAN bridge to the scenario's haptic arms: for each instrument whose input is `can_arm`
// (SocketCAN interface, e.g. can0) or `emulated_arm` (vesica-armsim over UDP on loopback: the
// arm with node id n listens on port 20000 + 2(n-1) and sends to 20001 + 2(n-1), so
// `vesica-armsim --node-id 1` is the left arm and `--node-id 2` the right), a device::CanArm
// opened on its transport, and a device::ArmSupervisor that clears a watchdog fault once its
// cause is gone and says in one line how the arm is. A scenario that names no arm (the default
// one) gets the emulated arms: node 1 for the grasper, node 2 for the hook. Tick() runs every
// arm's servo cycle (the haptic loop calls it at 1 kHz).

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "app/scenario/scenario.h"
#include "device/arm_supervisor.h"
#include "device/can_arm.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::app {

/// The link timing the bridge gives its arms on a host without real-time scheduling, chosen from
/// the measurement under load in docs/protocol.md ("Link timing on a loaded host"): the longest
/// silence between joint states seen at load 10-15 on 2 cores was 471 ms (twice that: no
/// flapping), the longest gap between the bridge's commands 250 ms; the node accepts a watchdog
/// of at most 100 ms, and the bridge clears the few trips it still gets.
inline constexpr std::chrono::milliseconds kBridgeLossTimeout{1000};
inline constexpr std::chrono::milliseconds kBridgeNodeWatchdog{100};

struct ArmBridgeOptions {
  /// Emulated arm n listens on udp_base_port + 2(n-1); the bridge on the port above it.
  /// 1 .. 65535 - 253 (room for node ids 1..127).
  int udp_base_port = 20000;
  /// No joint state for this long: "link lost", commands stop. > 0.
  std::chrono::nanoseconds loss_timeout = kBridgeLossTimeout;
  /// Written to each node's command watchdog before enabling: 0.5 .. 100 ms (the node's range).
  std::chrono::microseconds node_watchdog = kBridgeNodeWatchdog;
};

class ArmBridge {
 public:
  /// Opens the transports of the scenario's arm instruments ([0] grasper, [1] hook; a scenario
  /// with arms leaves the other instrument null) and starts their handshakes. Throws
  /// std::runtime_error naming the instrument, the interface or port and the reason when a
  /// transport cannot open or an arm refuses its settings: never a silent fallback.
  explicit ArmBridge(const Scenario& scenario, const ArmBridgeOptions& options = {});
  ~ArmBridge();
  ArmBridge(const ArmBridge&) = delete;
  ArmBridge& operator=(const ArmBridge&) = delete;

  static bool ScenarioUsesArms(const Scenario& scenario);
  std::array<device::HapticDevice*, 2> devices();
  /// One servo cycle of every arm, then its supervisor (the haptic thread, 1 kHz).
  void Tick();
  /// The user's command: clear every arm's latched fault (sent on the next Tick).
  void ResetFaults();
  /// Per arm ([0] left/grasper, [1] right/hook), only those the bridge drives.
  std::vector<device::ArmReport> Reports() const;
  /// The reports' texts, one line per arm ("left arm: ok\nright arm: FAULT over_current").
  std::string StatusLines() const;
  /// True while every arm reads ok.
  bool AllOk() const;
  /// One line per arm: instrument, status, link losses, automatic fault resets (diagnostics).
  std::string Describe() const;

 private:
  std::array<std::unique_ptr<fp::Transport>, 2> transports_;
  std::array<std::unique_ptr<device::CanArm>, 2> arms_;
  std::array<std::unique_ptr<device::ArmSupervisor>, 2> supervisors_;
  std::array<std::string, 2> names_;
};

}  // namespace vesica::app
