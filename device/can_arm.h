#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "device/arm_actuation.h"
#include "device/arm_calibration.h"
#include "device/calibration/homing.h"
#include "device/haptic_device.h"
#include "device/latency_statistics.h"
#include "device/link_monitor.h"
#include "device/node_calibration_reader.h"
#include "device/spherical_arm_kinematics.h"
#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::device {

struct CanArmConfig {
  std::uint8_t node_id = 1;                      ///< 1..127
  ArmActuation actuation = ArmActuation::Nominal();
  std::chrono::nanoseconds loss_timeout{std::chrono::milliseconds(10)};  ///< no state this long: lost
  std::chrono::nanoseconds retry_period{std::chrono::milliseconds(20)};  ///< handshake resend
  std::chrono::nanoseconds send_deadline{std::chrono::microseconds(500)};
  /// Written to the node's command watchdog before enabling; 0 keeps the node's setting (3 ms by
  /// default). A host without real-time scheduling needs more (tens of ms) or the node will trip.
  std::chrono::microseconds node_watchdog_timeout{0};
  double force_ramp_s = 0.05;          ///< force fades in over this after every enable, >= 0
  double velocity_filter_hz = 50.0;    ///< joint velocity estimate from positions, > 0
  /// While the node has no valid calibration, its calibration is read again this often (a
  /// technician may be calibrating it now), > 0.
  std::chrono::nanoseconds calibration_recheck{std::chrono::seconds(1)};
  std::string model_name = "Vesica 4-DOF spherical arm";
  /// Protocol 1.4: a node that says it is not homed since power-up is homed before it is enabled
  /// (calibration::HomeArm, slow and current-limited); false leaves it disabled, not homed.
  bool home_at_connection = true;
  calibration::HomingPlan homing;
  /// Waits until the transport's clock reaches a time, for the homing run (it owns the transport
  /// meanwhile); empty: sleeps on the transport's clock (a real bus, UDP).
  std::function<void(fp::Nanoseconds until)> homing_wait;
};

/// The host side of one arm on CAN (the bridge). Each Tick() is one servo cycle: read every
/// frame that arrived, keep the link, node and joint state, then send either a current command
/// (node enabled) or a SYNC (anything else, so the node's state is still sampled). The handshake
/// (Hello, reading the node's calibration, NMT start, explicit enable) runs inside Tick(), so
/// Open() never blocks and a test can drive the whole thing on a virtual bus with an injected
/// clock. Time is the transport's clock.
///
/// Calibration: the node applies encoder directions and offsets itself; the bridge reads the
/// calibration in force at every (re)connection (NodeCalibrationReader) and adds its friction and
/// gravity compensation to every command (ArmCalibration). A node without a valid calibration is
/// never enabled: status kNotCalibrated, calibration_problem() says why.
///
/// Loss: no joint state for loss_timeout -> status kLinkLost, commands stop (the node's watchdog
/// then zeroes torque and latches a fault). When states return, a latched fault is reported as
/// kNodeFault and nothing is re-enabled until ResetFault(): the user decides when force returns.
/// Homing (protocol 1.4): a node whose heartbeat says "not homed" (its encoders lost their
/// position while off) refuses Enable. Once its calibration is read and valid, the bridge homes it
/// (calibration::HomeArm on its own thread, which owns the transport meanwhile; Tick() then only
/// reports homing() and its progress), then connects again and enables it. A homing that stops
/// (fault, E-stop, lost link, a joint that cannot measure) leaves the arm disabled; ResetFault()
/// tries again. A node below 1.4 cannot say or do it: it is enabled as before.
/// Thread-safe: Tick() from the servo thread, the rest from any thread.
class CanArm final : public HapticDevice {
 public:
  CanArm(fp::Transport& transport, const CanArmConfig& config);
  ~CanArm() override;

  DeviceStatus Open() override;
  void Close() override;
  const DeviceCapabilities& Capabilities() const override { return capabilities_; }
  DeviceStatus Status() const override;
  JointState GetJointState() const override;
  ToolState GetToolState() const override;
  DeviceStatus SetTipForce(const Eigen::Vector3d& f_T) override;
  DeviceStatus ResetFault() override;

  /// One servo cycle; call at 1 kHz.
  void Tick();

  // Diagnostics.
  std::uint8_t node_id() const { return config_.node_id; }
  /// True once the node's calibration was read and is valid (then calibration() is in use).
  bool calibration_valid() const;
  ArmCalibration calibration() const;
  /// Why the node's calibration is not valid ("slot A: blank, slot B: blank"); empty while it is
  /// valid or still being read.
  std::string calibration_problem() const;
  ArmJoints joints() const;
  /// Homing under way, and how far (0..1).
  bool homing() const { return homing_running_.load(); }
  double homing_fraction() const { return homing_fraction_.load(); }
  /// Why the last homing stopped ("" if it did not, or none ran); the arm stays disabled.
  std::string homing_problem() const;
  /// The node's heartbeat says it is not homed (protocol 1.4).
  bool node_not_homed() const;
  std::uint32_t homing_count() const;  ///< homings finished (homed) since construction
  /// What the last finished homing found (offsets before and after, bus time, why it stopped).
  calibration::HomingResult last_homing() const;
  fp::NodeState node_state() const;
  fp::FaultCode node_fault() const;          ///< latched fault as last reported, None if none
  fp::FaultCode last_emergency() const;      ///< fault code of the last EMCY frame seen
  std::uint32_t emergency_count() const;
  MotorCurrentCommand last_command() const;
  LatencyStatistics::Summary loop_period() const;  ///< between Tick() calls
  LatencyStatistics::Summary round_trip() const;   ///< command/SYNC sent -> joint state back
  void ResetStatistics();                          ///< start a new measurement window
  bool answered() const;  ///< a joint state has arrived since Open()
  std::uint32_t node_boot_count() const;  ///< boot-up messages seen since Open(): the node restarted
  std::uint32_t link_loss_count() const;
  std::uint32_t link_restore_count() const;
  fp::DecodeErrorCounters decode_errors() const;
  std::uint64_t send_failures() const;
  /// Why Open() refused, or the last transport refusal; empty if none.
  std::string last_error() const;

 private:
  enum class Phase { kClosed, kConnecting, kRunning, kFault };

  void HandleFrame(const fp::TimedFrame& rx);
  /// The node may have restarted (link lost, or its boot-up message): its counters, version
  /// negotiation and RAM settings start afresh, so the handshake does too.
  void ForgetNodeSession();
  bool Send(const fp::Message& m, fp::Nanoseconds now);  ///< within config_.send_deadline
  bool Send(const fp::Message& m, fp::Nanoseconds now, fp::Nanoseconds deadline);
  void SendHandshake(fp::Nanoseconds now);
  /// One read of the node's calibration when one is due; true when it was sent.
  bool SendCalibrationRead(fp::Nanoseconds now);
  void SendCommand(fp::Nanoseconds now, bool zero);
  void StartHoming();
  /// Collects a finished homing run; true while one still owns the transport.
  bool HomingBusy();
  /// Asks a homing run to stop (the node ends its session: arm disabled, not homed) and waits for
  /// it; call with mu_ held (the run never takes it).
  void StopHoming();
  DeviceStatus StatusLocked() const;

  fp::Transport& transport_;
  CanArmConfig config_;
  DeviceCapabilities capabilities_;
  mutable std::mutex mu_;

  Phase phase_ = Phase::kClosed;
  LinkMonitor link_;
  LatencyStatistics loop_period_;
  LatencyStatistics round_trip_;
  fp::DecodeErrorCounters decode_errors_;
  fp::SequenceTracker state_sequence_;
  NodeCalibrationReader calibration_reader_;
  std::int64_t calibration_read_ns_ = -1;  ///< when the last read of an invalid calibration ended

  // Node as last reported.
  fp::NodeState node_state_ = fp::NodeState::Boot;
  bool node_enabled_ = false;
  bool negotiated_ = false;
  fp::FaultCode node_fault_ = fp::FaultCode::None;
  fp::FaultCode last_emergency_ = fp::FaultCode::None;
  std::uint32_t emergency_count_ = 0;
  fp::Limiter limiter_ = fp::Limiter::None;

  // Arm state.
  ArmJoints q_;
  Eigen::Vector4d qd_ = Eigen::Vector4d::Zero();
  std::int64_t last_state_ns_ = -1;
  double jaw_rad_ = 0.0;
  std::uint32_t buttons_ = 0;

  // Commands.
  Eigen::Vector3d f_request_T_ = Eigen::Vector3d::Zero();
  MotorCurrentCommand last_command_;
  std::int64_t enabled_since_ns_ = -1;
  std::int64_t last_handshake_ns_ = -1;
  std::int64_t last_tick_ns_ = -1;
  std::int64_t request_sent_ns_ = -1;  ///< awaiting the joint state that answers it
  std::uint8_t sync_counter_ = 0;
  std::uint8_t command_counter_ = 0;
  std::uint8_t control_counter_ = 0;
  bool reset_requested_ = false;
  bool watchdog_configured_ = false;
  std::uint64_t send_failures_ = 0;
  std::uint32_t node_boot_count_ = 0;
  std::string last_error_;

  // Homing (protocol 1.4).
  bool node_not_homed_ = false;
  bool homing_failed_ = false;  ///< not retried until ResetFault()
  std::string homing_problem_;
  std::uint32_t homing_count_ = 0;
  std::thread homing_thread_;
  std::atomic<bool> homing_running_{false};
  std::atomic<double> homing_fraction_{0.0};
  std::mutex homing_link_mu_;                            ///< guards homing_link_
  calibration::CalibrationLink* homing_link_ = nullptr;  ///< the run's link while it lasts (Close aborts it)
  calibration::HomingResult homing_result_;  ///< written by the homing thread, read after join
};

}  // namespace vesica::device
