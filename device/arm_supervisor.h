#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

#include "device/can_arm.h"

namespace vesica::device {

/// One arm as the surgeon's view shows it: plain data, `text` ready to print.
struct ArmReport {
  DeviceStatus status = DeviceStatus::kNotOpen;
  fp::FaultCode fault = fp::FaultCode::None;  ///< the node's latched fault while status is kNodeFault
  std::uint32_t link_losses = 0;
  std::uint32_t automatic_fault_resets = 0;  ///< faults cleared because their cause was gone
  std::uint32_t requested_fault_resets = 0;  ///< faults cleared on the user's command
  /// One line: "left arm: ok", "right arm: FAULT over_current", "right arm: link lost",
  /// "left arm: no answer from node 1 on UDP 127.0.0.1:20000", "left arm (node 1): no valid
  /// calibration (slot A: blank, slot B: blank); run `vesica-calibrate calibrate 1`", "left arm:
  /// homing 40%", "left arm (node 1): not homed since power-up (...); reset faults to home it
  /// again, or run `vesica-calibrate home 1`".
  std::string text;
};

struct ArmSupervisorConfig {
  std::string name = "arm";  ///< how the view names the arm, e.g. "left arm"
  std::string link;          ///< where its node is, for "no answer" messages, e.g. "node 1 on UDP 127.0.0.1:20000"
  /// What the technician runs for an arm without a valid calibration; empty: `vesica-calibrate
  /// calibrate N` (N the node id; the tool's default bus is vesica-armsim's UDP).
  std::string calibrate_command;
  /// What the technician runs to home an arm that the bridge could not home; empty:
  /// `vesica-calibrate home N`.
  std::string home_command;
  /// A command-watchdog fault is the host's own doing (its commands stopped: link loss, a stall):
  /// once states arrive again for this long the supervisor sends ResetFault. > 0.
  std::chrono::nanoseconds watchdog_reset_after{std::chrono::milliseconds(200)};
  /// Between automatic resets while a fault stays (the node refuses, or trips again at once). > 0.
  std::chrono::nanoseconds reset_retry_period{std::chrono::seconds(1)};
  /// Connecting without a single answer for this long is reported as "no answer". > 0.
  std::chrono::nanoseconds no_answer_after{std::chrono::seconds(2)};
};

/// Keeps one CanArm usable for a whole session: clears a node fault when its cause is gone (a
/// command watchdog once the link is back) or on the user's command, without reopening anything,
/// and says in one line how the arm is. Other faults (E-stop, over-current, over-speed, range,
/// voltage, temperature, parameters, protocol) wait for the user: they mean something happened
/// at the arm that a person should see before force returns.
/// Thread-safe: Tick() from the servo thread after CanArm::Tick(), the rest from any thread.
class ArmSupervisor {
 public:
  ArmSupervisor(CanArm& arm, ArmSupervisorConfig config);

  /// One servo cycle at time `now` (the arm's transport clock).
  void Tick(fp::Nanoseconds now);
  /// The user's command: clear the arm's latched fault on the next Tick().
  void RequestFaultReset();
  ArmReport Report() const;

 private:
  struct Seen {
    DeviceStatus status;
    fp::FaultCode fault;
    bool answered;
    bool silent_too_long;
    std::uint8_t node_id;
    std::string calibration_problem;
    bool homing = false;
    double homing_fraction = 0.0;
    bool not_homed = false;
    std::string homing_problem;
  };
  static std::string Describe(const ArmSupervisorConfig& config, const Seen& seen);

  CanArm& arm_;
  const ArmSupervisorConfig config_;
  std::atomic<bool> reset_requested_{false};
  mutable std::mutex mu_;
  std::int64_t first_tick_ns_ = -1;
  std::int64_t fault_seen_ns_ = -1;  ///< when the current watchdog fault was first seen with the link up
  std::int64_t last_reset_ns_ = -1;
  bool silent_too_long_ = false;
  std::uint32_t automatic_resets_ = 0;
  std::uint32_t requested_resets_ = 0;
};

}  // namespace vesica::device
