#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::device::calibration {

struct CalibrationLinkConfig {
  std::uint8_t node_id = 1;                                       ///< 1..127
  fp::Nanoseconds period{std::chrono::milliseconds(1)};           ///< servo period, > 0
  fp::Nanoseconds loss_timeout{std::chrono::milliseconds(50)};    ///< no joint state this long: link lost
  fp::Nanoseconds reply_timeout{std::chrono::milliseconds(300)};  ///< for each request's answer
  fp::Nanoseconds send_deadline{std::chrono::microseconds(500)};
};

/// The node as it introduced itself (Identity).
struct NodeIdentity {
  std::uint8_t node = 0;
  std::uint8_t protocol_major = 0;
  std::uint8_t min_minor = 0;
  std::uint8_t max_minor = 0;
  std::uint8_t negotiated_minor = 0xFF;
  std::uint32_t serial = 0;
};

/// What the node reported last, joint order yaw, pitch, insertion.
struct LinkSample {
  double t_s = 0.0;                   ///< transport time of the last joint state
  std::array<double, 3> position{};   ///< rad, rad, m (the node's calibration applied)
  std::array<double, 3> current_A{};  ///< measured motor currents (100 Hz)
  fp::Limiter limiter = fp::Limiter::None;
};

/// The calibration tool's connection to one node over any transport: version check, parameters,
/// the node's calibration session and its procedures, and the servo cycle. Everything that should
/// stop a calibration throws CalibrationAbort: a node fault or E-stop, no joint state for
/// loss_timeout, a refused request, no answer, or RequestAbort() from any thread.
///
/// Time is the transport's clock; `wait(t)` returns once that clock has reached t (sleeps on a
/// real bus; on the virtual bus it advances the bus and the emulated arm).
class CalibrationLink {
 public:
  using Waiter = std::function<void(fp::Nanoseconds until)>;
  /// The protocol minor that brought the calibration session and slots.
  static constexpr std::uint8_t kCalibrationMinor = 1;

  CalibrationLink(fp::Transport& transport, Waiter wait, const CalibrationLinkConfig& config = {});

  /// Hello and Identity. Throws kProtocolTooOld for a node below protocol 1.1, kNoAnswer when
  /// nothing answers.
  NodeIdentity Connect();
  /// Fault reset when the node has one latched (a calibration starts from a fault-free node).
  void ClearFault();

  fp::ParameterResponse Read(std::uint16_t index);
  std::uint32_t ReadU32(std::uint16_t index) { return Read(index).raw_value; }
  float ReadF32(std::uint16_t index);
  void WriteU32(std::uint16_t index, std::uint32_t value);
  void WriteI32(std::uint16_t index, std::int32_t value);
  void WriteF32(std::uint16_t index, float value);
  /// Parameter Save: inside a session it stores the results and ends the session.
  void Save();

  /// Opens the node's calibration session (pre-operational first): the joints in mask may be
  /// driven with at most max_current_A.
  void BeginSession(std::uint8_t joint_mask, double max_current_A);
  /// Ends the session unsaved (the node reloads its stored calibration). Never throws.
  void AbortSession() noexcept;
  bool session_open() const { return session_open_; }

  /// Runs a node procedure (find index, current offset) to its end; the host's commands keep the
  /// other joints served meanwhile. Returns the procedure's result field.
  std::int32_t RunNodeProcedure(fp::CalibrationProcedure procedure, std::uint8_t joint_mask, double max_current_A,
                                double timeout_s, const std::function<std::array<double, 3>()>& command);

  /// Protocol 1.4, inside the session: the position offsets now in the node's RAM are this
  /// power-up's frame (homing found them): the node is homed and keeps them after the session.
  void DeclareHome();
  /// Protocol 1.4: the node's last heartbeat said it is not homed (Enable refused until it is).
  bool node_not_homed() const { return node_not_homed_; }

  /// Protocol 1.2: asks the node (inside the session) for its raw hand sensors, reported every
  /// 20 ms until the session ends, and waits for the first report. Throws kProtocolTooOld for a
  /// node that negotiated less than 1.2, naming `what`.
  void StartHandSensorReadout(const std::string& what);
  /// The latest raw reading of hand sensor k (0 roll, 1 jaw, 2 pedal) and its bus time (< 0: none).
  std::int32_t hand_raw(int k) const { return hand_raw_[k]; }
  double hand_raw_t_s(int k) const { return hand_raw_t_s_[k]; }
  /// The minor negotiated at Connect (0xFF before).
  std::uint8_t negotiated_minor() const { return identity_.negotiated_minor; }

  /// One servo period: send the currents (a SYNC outside a session), wait a period, read what came.
  const LinkSample& Cycle(const std::array<double, 3>& amps);

  void RequestAbort() { abort_requested_ = true; }
  const LinkSample& sample() const { return sample_; }
  /// The latched fault as last reported (heartbeat, EMCY); None before either was seen.
  fp::FaultCode node_fault() const { return node_fault_; }
  /// Servo periods until a heartbeat has come (it carries the latched fault), at most 0.3 s.
  void AwaitHeartbeat();
  double now_s() const;
  std::uint8_t node_id() const { return config_.node_id; }

 private:
  void Send(const fp::Message& m);
  void ReceiveAll();
  void Handle(const fp::Message& m, fp::Nanoseconds t);
  void CheckStop();
  fp::ParameterResponse Ask(const fp::ParameterRequest& request);
  void WaitPeriod();

  fp::Transport& transport_;
  Waiter wait_;
  CalibrationLinkConfig config_;
  std::atomic<bool> abort_requested_{false};
  LinkSample sample_;
  std::array<double, 3> last_amps_{};
  fp::Nanoseconds next_{0};
  fp::Nanoseconds last_state_{-1};
  bool session_open_ = false;
  bool watch_faults_ = false;  ///< from the session's start to its save: a fault stops everything
  bool heartbeat_seen_ = false;
  bool node_not_homed_ = false;
  fp::FaultCode node_fault_ = fp::FaultCode::None;
  fp::NodeState node_state_ = fp::NodeState::Boot;
  bool identity_seen_ = false;
  NodeIdentity identity_;
  bool response_seen_ = false;
  fp::ParameterResponse response_;
  bool progress_seen_ = false;
  fp::CalibrationProgress progress_;
  std::array<std::int32_t, 3> hand_raw_{};
  std::array<double, 3> hand_raw_t_s_{-1.0, -1.0, -1.0};
  std::uint8_t command_counter_ = 0;
  std::uint8_t sync_counter_ = 0;
  std::uint8_t control_counter_ = 0;
};

}  // namespace vesica::device::calibration
