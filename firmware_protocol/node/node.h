// Reference firmware node of one Vesica arm: NMT state machine, explicit enable, command watchdog,
// current/torque/velocity/joint-range limits with the active limiter reported, E-stop, latched
// faults with EMCY and history, typed parameters in two CRC-protected calibration slots (A/B),
// node-run calibration procedures and the host-driven calibration session.
// Use (firmware main loop or the arm emulator):
//   Node<Board> node(board, serial);  node.boot(now_us);
//   for each received frame: node.on_frame(frame, now_us);
//   every control period:   node.tick(now_us);  while (node.pop_tx(f)) bus.send(f);
// Times are microseconds of a monotonic clock the caller owns (injected in tests).
// Freestanding C++17: no heap, no exceptions, no OS calls; Hw must satisfy NodeHardware.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/node/calibration_slot.h"
#include "firmware_protocol/node/fault_history.h"
#include "firmware_protocol/node/hand_calibration.h"
#include "firmware_protocol/node/node_hardware.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::fp {

template <VESICA_NODE_HARDWARE Hw>
class Node {
 public:
  static constexpr std::size_t kTxQueueDepth = 32;
  static constexpr std::uint32_t kCalibrationProgressPeriod_us = 100'000;
  static constexpr std::uint32_t kCurrentOffsetSamples = 200;
  static constexpr std::uint64_t kFindIndexTimeout_us = 10'000'000;
  static constexpr float kFindIndexCreepFraction = 0.03f;  // of max_velocity: 0.18 rad/s, 30 mm/s
  // Protocol 1.2: the calibration session's own command watchdog and speed bound. A session's
  // motions are slow and current-limited, so a host that stalls (a loaded, non-real-time host) may
  // leave the last command in force longer than in operation; the speed bound keeps what it can
  // do in that time small (docs/protocol.md section 11, "Watchdog in a calibration session").
  static constexpr std::uint32_t kSessionWatchdog_us = 250'000;
  static constexpr float kSessionSpeedFraction = 0.5f;  // of max_velocity: 3 rad/s, 0.5 m/s
  static constexpr std::uint32_t kHandSensorPeriod_us = 20'000;  // raw hand-sensor readout, 50 Hz

  Node(Hw& hw, std::uint32_t serial) : hw_(hw), serial_(serial) {}

  // For emulating firmware of an older protocol minor (version negotiation tests, armsim
  // --firmware-minor): the Identity says so, and below minor 3 the node has no layout-2
  // parameters and stores layout 1, as that firmware did. Call before boot.
  void emulate_firmware_minor(std::uint8_t minor) { max_minor_ = minor < kProtocolMinor ? minor : kProtocolMinor; }
  // A board whose encoders lose their position while off (incremental, no battery-backed
  // counter): from protocol 1.4 the node starts every boot not homed, flags it in its heartbeat
  // and refuses Enable until a host has homed it (CalibrationProcedure::Home). Call before boot.
  void require_homing(bool required) { homing_required_ = required; }

  // Power-on / NMT reset node: load parameters from the newest valid calibration slot, send the
  // boot-up heartbeat and Identity, enter PreOperational. No valid slot but a corrupt one latches
  // FaultCode::ParameterCrc (defaults in use); blank storage is a new board (defaults, no fault).
  void boot(std::uint64_t now_us);
  void on_frame(const CanFrame& frame, std::uint64_t now_us);
  void tick(std::uint64_t now_us);
  bool pop_tx(CanFrame& out);

  NodeState state() const { return faults_.latched() != FaultCode::None ? NodeState::Fault : nmt_state_; }
  bool enabled() const { return enabled_; }
  FaultCode latched_fault() const { return faults_.latched(); }
  Limiter active_limiter() const { return limiter_; }
  const JointArray& applied_current() const { return applied_; }
  const DecodeErrorCounters& decode_errors() const { return decode_errors_; }
  const ParameterStore& parameters() const { return params_; }
  const FaultHistory& fault_history() const { return faults_; }
  std::uint8_t node_id() const { return node_id_; }
  std::uint8_t negotiated_minor() const { return negotiated_minor_; }
  std::uint8_t max_minor() const { return max_minor_; }
  std::uint16_t stored_layout() const { return stored_layout_; }  // of the booted slot; 0: none
  std::uint32_t tx_overflows() const { return tx_overflows_; }
  CalibrationStatus calibration_status() const { return cal_status_; }
  bool calibration_session_open() const { return session_open_; }
  int active_slot() const { return active_slot_; }  // -1: running on defaults
  bool homed() const { return homed_; }
  bool homing_required() const { return homing_required_ && max_minor_ >= kHomingMinor; }
  StorageResult slot_status(int s) const { return slot_status_[s]; }
  std::uint32_t slot_generation(int s) const { return slot_generation_[s]; }

 private:
  void queue(const Message& m);
  void raise(FaultCode code, std::uint8_t joint, std::int16_t detail);
  void send_joint_state();
  void send_heartbeat();
  void send_identity();
  void handle_nmt(const Nmt& m, std::uint64_t now_us);
  void handle_control(const Control& m, std::uint64_t now_us);
  void handle_parameter(const ParameterRequest& m);
  void handle_hello(const Hello& m);
  void handle_calibration(const CalibrationCommand& m, std::uint64_t now_us);
  void check_faults(const HardwareSample& s, std::uint64_t now_us);
  JointArray limited_output(const HardwareSample& s);
  JointArray calibration_output(const HardwareSample& s, std::uint64_t now_us);
  void finish_calibration(CalibrationStatus status, std::int32_t result);
  JointArray session_output(const HardwareSample& s);
  void end_session(CalibrationStatus status);
  void declare_home();
  void keep_home_after_save();
  bool offsets_are_home() const;
  StorageResult load_parameters();
  void reload_parameters();
  bool save_parameters();
  void sync_slot_parameters();
  int encoder_direction(int j) const {
    const std::uint32_t raw = params_.u32(static_cast<std::uint16_t>(param::kEncoderDirection + j));
    return static_cast<std::int32_t>(raw) < 0 ? -1 : 1;
  }
  void sync_fault_parameters();
  static float clampf(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

  Hw& hw_;
  std::uint32_t serial_;
  ParameterStore params_;
  FaultHistory faults_;
  DecodeErrorCounters decode_errors_;
  SequenceTracker command_sequence_;
  NodeState nmt_state_ = NodeState::Boot;
  std::uint8_t node_id_ = 1;
  std::uint8_t negotiated_minor_ = 0xFF;
  std::uint8_t max_minor_ = kProtocolMinor;
  std::uint16_t stored_layout_ = 0;
  bool enabled_ = false;
  std::uint64_t last_command_us_ = 0;
  CommandMode command_mode_ = CommandMode::MotorCurrent;
  JointArray command_{};
  JointArray applied_{};
  JointArray position_{};
  Limiter limiter_ = Limiter::Disabled;
  std::uint8_t joint_state_counter_ = 0;
  std::uint8_t aux_counter_ = 0;
  std::uint8_t current_state_counter_ = 0;
  std::uint64_t next_heartbeat_us_ = 0;
  std::uint64_t next_aux_us_ = 0;
  HardwareSample last_sample_{};
  // Calibration in progress.
  CalibrationProcedure cal_procedure_ = CalibrationProcedure::Abort;
  CalibrationStatus cal_status_ = CalibrationStatus::Idle;
  std::uint8_t cal_mask_ = 0;
  std::uint8_t cal_joint_ = 0;
  float cal_max_current_ = 0;
  std::uint32_t cal_samples_ = 0;
  JointArray cal_sum_{};
  std::uint64_t cal_started_us_ = 0;
  std::uint64_t next_cal_progress_us_ = 0;
  // Host-driven calibration session (CalibrationProcedure::Session).
  bool session_open_ = false;
  bool hand_readout_ = false;  // protocol 1.2: raw hand sensors reported while the session lasts
  std::uint64_t next_hand_us_ = 0;
  std::uint8_t session_mask_ = 0;
  float session_max_current_ = 0;
  // Homing (protocol 1.4): whether this power-up's frame is known, and its position offsets.
  bool homing_required_ = false;
  bool homed_ = true;
  bool has_home_offset_ = false;
  bool home_declared_in_session_ = false;
  JointArray home_offset_{};
  // Calibration slots as found at boot / after the last save.
  StorageResult slot_status_[slot::kCount] = {StorageResult::BadMagic, StorageResult::BadMagic};
  std::uint32_t slot_generation_[slot::kCount] = {};
  int active_slot_ = -1;
  // Transmit ring.
  CanFrame tx_[kTxQueueDepth];
  std::size_t tx_head_ = 0;
  std::size_t tx_size_ = 0;
  std::uint32_t tx_overflows_ = 0;
};

// ---- implementation (header-only because Node is a template) ----

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::boot(std::uint64_t now_us) {
  nmt_state_ = NodeState::Boot;
  enabled_ = false;
  applied_ = JointArray{};
  command_ = JointArray{};
  hw_.apply_currents(applied_);
  negotiated_minor_ = 0xFF;
  command_sequence_.reset();
  cal_status_ = CalibrationStatus::Idle;
  session_open_ = false;
  hand_readout_ = false;
  faults_.clear_latch();
  // The encoders count from wherever the arm is now: the stored offsets hold only if it did not move.
  homed_ = !homing_required();
  has_home_offset_ = false;
  home_declared_in_session_ = false;

  const StorageResult loaded = load_parameters();
  std::uint32_t history[param::kFaultHistoryDepth];
  for (int k = 0; k < param::kFaultHistoryDepth; ++k) history[k] = params_.u32(param::kFaultHistory + k);
  faults_.restore(params_.u32(param::kFaultHistoryCount), history);
  params_.set_internal(param::kSerial, serial_);
  node_id_ = static_cast<std::uint8_t>(params_.u32(param::kNodeId));

  send_heartbeat();  // boot-up message: heartbeat with state Boot (CANopen 0x00)
  nmt_state_ = NodeState::PreOperational;
  send_identity();
  // Blank storage (BadMagic) is a new board: defaults, no fault. No valid slot and a corrupt one
  // means the calibration is gone: the operator must know.
  if (loaded != StorageResult::Ok && loaded != StorageResult::BadMagic)
    raise(FaultCode::ParameterCrc, 0xFF, static_cast<std::int16_t>(loaded));
  next_heartbeat_us_ = now_us + 1000ull * params_.u32(param::kHeartbeatPeriod_ms);
  next_aux_us_ = now_us;
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::on_frame(const CanFrame& frame, std::uint64_t now_us) {
  Message m;
  const DecodeError e = decode(frame, m);
  if (e != DecodeError::None) {
    decode_errors_.add(e);
    params_.set_internal(param::kDecodeErrorCount, decode_errors_.total());
    return;
  }
  const MessageKind kind = kind_of(m);
  if (spec_of(kind).per_node && node_of(m) != node_id_) return;  // another node's traffic
  if (nmt_state_ == NodeState::Boot) return;
  switch (kind) {
    case MessageKind::Nmt: handle_nmt(std::get<Nmt>(m), now_us); break;
    case MessageKind::EStop: raise(FaultCode::EmergencyStop, 0xFF, std::get<EStop>(m).source_node); break;
    case MessageKind::Sync:
      if (nmt_state_ != NodeState::Stopped) send_joint_state();
      break;
    case MessageKind::CurrentCommand: {
      if (nmt_state_ == NodeState::Stopped) break;
      const CurrentCommand& c = std::get<CurrentCommand>(m);
      const DecodeError seq = command_sequence_.check(c.counter);
      if (seq != DecodeError::None) {
        decode_errors_.add(seq);
        params_.set_internal(param::kDecodeErrorCount, decode_errors_.total());
        break;
      }
      params_.set_internal(param::kLostCommandCount, command_sequence_.lost_frames());
      command_mode_ = c.mode;
      command_ = c.value;
      last_command_us_ = now_us;
      send_joint_state();
      break;
    }
    case MessageKind::Control: handle_control(std::get<Control>(m), now_us); break;
    case MessageKind::Hello: handle_hello(std::get<Hello>(m)); break;
    case MessageKind::ParameterRequest:
      if (nmt_state_ != NodeState::Stopped) handle_parameter(std::get<ParameterRequest>(m));
      break;
    case MessageKind::CalibrationCommand:
      if (nmt_state_ != NodeState::Stopped) handle_calibration(std::get<CalibrationCommand>(m), now_us);
      break;
    default: break;  // node-to-host messages from other nodes
  }
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::handle_nmt(const Nmt& m, std::uint64_t now_us) {
  if (m.target_node != 0 && m.target_node != node_id_) return;
  // A calibration session lives in pre-operational only; anything else ends it unsaved.
  if (session_open_ && m.command != NmtCommand::EnterPreOperational) end_session(CalibrationStatus::Aborted);
  switch (m.command) {
    case NmtCommand::Start: nmt_state_ = NodeState::Operational; break;
    case NmtCommand::Stop: nmt_state_ = NodeState::Stopped; enabled_ = false; break;
    case NmtCommand::EnterPreOperational: nmt_state_ = NodeState::PreOperational; enabled_ = false; break;
    case NmtCommand::ResetNode: {
      const FaultCode latched = faults_.latched();
      boot(now_us);
      if (latched != FaultCode::None && faults_.latched() == FaultCode::None) faults_.relatch(latched);  // a reset is no fault reset
      return;
    }
    case NmtCommand::ResetCommunication:
      enabled_ = false;
      negotiated_minor_ = 0xFF;
      command_sequence_.reset();
      nmt_state_ = NodeState::Boot;
      send_heartbeat();
      nmt_state_ = NodeState::PreOperational;
      send_identity();
      return;
  }
  send_heartbeat();  // acknowledge the transition at once
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::handle_control(const Control& m, std::uint64_t now_us) {
  switch (m.command) {
    case ControlCommand::Enable:
      // Explicit enable: only operational, fault-free, negotiated, E-stop loop closed, no calibration.
      if (nmt_state_ == NodeState::Operational && faults_.latched() == FaultCode::None && negotiated_minor_ != 0xFF &&
          !last_sample_.estop_input && cal_status_ != CalibrationStatus::Running && !session_open_ && homed_) {
        enabled_ = true;
        command_ = JointArray{};
        command_sequence_.reset();
        last_command_us_ = now_us;  // the watchdog starts counting at enable
      }
      break;
    case ControlCommand::Disable: enabled_ = false; break;
    case ControlCommand::FaultReset:
      if (faults_.latched() != FaultCode::None && !last_sample_.estop_input) {
        faults_.clear_latch();
        enabled_ = false;
        queue(Emergency{node_id_, FaultCode::None, 0xFF,
                        static_cast<std::uint8_t>(faults_.count() > 255 ? 255 : faults_.count()), 0});
      }
      break;
  }
  send_heartbeat();
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::handle_hello(const Hello& m) {
  // Major must match; the minor is the highest both sides speak.
  if (m.protocol_major == kProtocolMajor) {
    negotiated_minor_ = m.protocol_minor < max_minor_ ? m.protocol_minor : max_minor_;
  } else {
    negotiated_minor_ = 0xFF;
    enabled_ = false;
  }
  send_identity();
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::handle_parameter(const ParameterRequest& m) {
  ParameterResponse r{node_id_, m.op, false, m.type, m.index, 0};
  AbortCode abort = AbortCode::None;
  const int slot_index = parameter_slot(m.index);
  const bool older_firmware_lacks = max_minor_ < kLayout2Minor && slot_index >= 0 &&
                                    parameter_layout(static_cast<std::size_t>(slot_index)) > 1;
  if (older_firmware_lacks && (m.op == ParameterOp::Read || m.op == ParameterOp::Write)) {
    r.aborted = true;
    r.raw_value = static_cast<std::uint32_t>(AbortCode::NoSuchParameter);
    queue(r);
    return;
  }
  switch (m.op) {
    case ParameterOp::Read: abort = params_.read(m.index, r.type, r.raw_value); break;
    case ParameterOp::Write:
      // Limits never change under torque: writes only while disabled. Nor while a fault is
      // latched: a write sent before the host saw the fault (an E-stop ending a calibration
      // session, whose reload brought the stored values back) must not land afterwards.
      abort = enabled_ || faults_.latched() != FaultCode::None ? AbortCode::WrongState
                                                              : params_.write(m.index, m.type, m.raw_value);
      if (abort == AbortCode::None) r.raw_value = m.raw_value;
      break;
    case ParameterOp::Save: {
      if (enabled_ || cal_status_ == CalibrationStatus::Running) { abort = AbortCode::WrongState; break; }
      sync_fault_parameters();
      if (!save_parameters()) abort = AbortCode::StorageFailed;
      else
        keep_home_after_save();
      // A save is how a calibration session keeps its results; a failed one keeps the old.
      if (session_open_) end_session(abort == AbortCode::None ? CalibrationStatus::Done : CalibrationStatus::Failed);
      break;
    }
    case ParameterOp::RestoreDefaults:
      if (enabled_) { abort = AbortCode::WrongState; break; }
      params_.restore_defaults();
      params_.set_internal(param::kSerial, serial_);
      params_.set_internal(param::kNodeId, node_id_);  // the id changes only through a write + reset
      break;
  }
  if (abort != AbortCode::None) {
    r.aborted = true;
    r.raw_value = static_cast<std::uint32_t>(abort);
  }
  queue(r);
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::handle_calibration(const CalibrationCommand& m, std::uint64_t now_us) {
  if (m.procedure == CalibrationProcedure::Abort) {
    if (cal_status_ == CalibrationStatus::Running) finish_calibration(CalibrationStatus::Aborted, 0);
    if (session_open_) end_session(CalibrationStatus::Aborted);
    return;
  }
  if (m.procedure == CalibrationProcedure::Home) {
    // Inside a session only (the host found the frame there), and only firmware that knows it.
    if (!session_open_ || max_minor_ < kHomingMinor) {
      queue(CalibrationProgress{node_id_, m.procedure, CalibrationStatus::Failed, 0, 0, -1});
      return;
    }
    declare_home();
    queue(CalibrationProgress{node_id_, m.procedure, CalibrationStatus::Done, 100, 0, 0});
    return;
  }
  if (m.procedure == CalibrationProcedure::HandSensors) {
    // Inside a session only: nothing moves, the node reports what the hand sensors read.
    if (!session_open_) {
      queue(CalibrationProgress{node_id_, m.procedure, CalibrationStatus::Failed, 0, 0, -1});
      return;
    }
    hand_readout_ = true;
    next_hand_us_ = now_us;
    return;
  }
  // Calibration moves motors on its own authority: only pre-operational, disabled and fault-free.
  if (nmt_state_ != NodeState::PreOperational || enabled_ || faults_.latched() != FaultCode::None ||
      m.joint_mask == 0 || cal_status_ == CalibrationStatus::Running ||
      (m.procedure == CalibrationProcedure::Session && session_open_)) {
    queue(CalibrationProgress{node_id_, m.procedure, CalibrationStatus::Failed, 0, 0, -1});
    return;
  }
  if (m.procedure == CalibrationProcedure::Session) {
    // The host drives the masked joints with CurrentCommand, bounded by max_current; the
    // watchdog runs as when enabled, so a lost host ends the session within its timeout.
    session_open_ = true;
    home_declared_in_session_ = false;
    session_mask_ = m.joint_mask;
    session_max_current_ = m.max_current;
    command_ = JointArray{};
    command_mode_ = CommandMode::MotorCurrent;
    command_sequence_.reset();
    last_command_us_ = now_us;
    queue(CalibrationProgress{node_id_, m.procedure, CalibrationStatus::Running, 0, 0, 0});
    return;
  }
  cal_procedure_ = m.procedure;
  cal_status_ = CalibrationStatus::Running;
  cal_mask_ = m.joint_mask;
  cal_max_current_ = m.max_current;
  cal_samples_ = 0;
  cal_sum_ = JointArray{};
  cal_joint_ = 0;
  while (cal_joint_ < kJointCount && !(cal_mask_ & (1u << cal_joint_))) ++cal_joint_;
  cal_started_us_ = now_us;
  next_cal_progress_us_ = now_us;
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::finish_calibration(CalibrationStatus status, std::int32_t result) {
  cal_status_ = status;
  queue(CalibrationProgress{node_id_, cal_procedure_, status,
                            static_cast<std::uint8_t>(status == CalibrationStatus::Done ? 100 : 0),
                            static_cast<std::uint8_t>(cal_joint_ < kJointCount ? cal_joint_ : 0), result});
}

template <VESICA_NODE_HARDWARE Hw>
JointArray Node<Hw>::calibration_output(const HardwareSample& s, std::uint64_t now_us) {
  JointArray out{};
  std::uint8_t percent = 0;
  if (cal_procedure_ == CalibrationProcedure::CurrentOffset) {
    // Zero output; the mean measured current is the sensor offset.
    for (int j = 0; j < kJointCount; ++j) cal_sum_[j] += s.current[j];
    ++cal_samples_;
    percent = static_cast<std::uint8_t>(100 * cal_samples_ / kCurrentOffsetSamples);
    if (cal_samples_ >= kCurrentOffsetSamples) {
      std::int32_t result_uA = 0;
      for (int j = 0; j < kJointCount; ++j) {
        if (!(cal_mask_ & (1u << j))) continue;
        // The sample already has the offset in force subtracted: the mean is what is left.
        const float offset = params_.f32(static_cast<std::uint16_t>(param::kCurrentOffset + j)) +
                             cal_sum_[j] / static_cast<float>(cal_samples_);
        params_.set_internal_f32(static_cast<std::uint16_t>(param::kCurrentOffset + j), clampf(offset, -5, 5));
        result_uA = static_cast<std::int32_t>(std::lround(offset * 1e6f));
        cal_joint_ = static_cast<std::uint8_t>(j);
      }
      finish_calibration(CalibrationStatus::Done, result_uA);
      return out;
    }
  } else if (cal_procedure_ == CalibrationProcedure::FindIndex) {
    // Creep each selected joint with a bounded current until its encoder index pulse; the raw
    // position there becomes the joint's zero.
    if (now_us - cal_started_us_ > kFindIndexTimeout_us) {
      finish_calibration(CalibrationStatus::Failed, cal_joint_);
      return out;
    }
    if (s.index_seen[cal_joint_]) {
      // The sample carries the offset in force: shift it so that the index reads zero.
      const auto index = static_cast<std::uint16_t>(param::kPositionOffset + cal_joint_);
      const float raw = s.position[cal_joint_] - params_.f32(index);
      params_.set_internal_f32(index, clampf(-raw, -10, 10));
      const std::uint8_t done_joint = cal_joint_;
      ++cal_joint_;
      while (cal_joint_ < kJointCount && !(cal_mask_ & (1u << cal_joint_))) ++cal_joint_;
      if (cal_joint_ >= kJointCount) {
        cal_joint_ = done_joint;
        finish_calibration(CalibrationStatus::Done, static_cast<std::int32_t>(std::lround(-raw * 1e6f)));
        return out;
      }
      cal_started_us_ = now_us;
    } else {
      const auto jj = static_cast<std::uint16_t>(cal_joint_);
      const float limit = params_.f32(static_cast<std::uint16_t>(param::kMaxCurrent + jj));
      // Creep: no current above the creep speed, so the index is seen where it is, not a
      // tick's travel later (and a joint at rest against friction still starts).
      const float creep = kFindIndexCreepFraction * params_.f32(static_cast<std::uint16_t>(param::kMaxVelocity + jj));
      out[cal_joint_] = s.velocity[cal_joint_] > creep ? 0.0f : clampf(cal_max_current_, 0, limit);
    }
    percent = static_cast<std::uint8_t>(100 * cal_joint_ / kJointCount);
  }
  if (now_us >= next_cal_progress_us_) {
    next_cal_progress_us_ = now_us + kCalibrationProgressPeriod_us;
    queue(CalibrationProgress{node_id_, cal_procedure_, CalibrationStatus::Running, percent > 100 ? std::uint8_t{100} : percent,
                              cal_joint_, 0});
  }
  return out;
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::tick(std::uint64_t now_us) {
  if (nmt_state_ == NodeState::Boot) return;
  HardwareSample s = hw_.sense();
  for (int j = 0; j < kJointCount; ++j) {
    const float dir = static_cast<float>(encoder_direction(j));
    s.position[j] = dir * s.position[j] + params_.f32(static_cast<std::uint16_t>(param::kPositionOffset + j));
    s.velocity[j] *= dir;
    s.current[j] -= params_.f32(static_cast<std::uint16_t>(param::kCurrentOffset + j));
  }
  last_sample_ = s;
  position_ = s.position;
  check_faults(s, now_us);
  const bool faulted = faults_.latched() != FaultCode::None;
  if (session_open_ && (faulted || nmt_state_ != NodeState::PreOperational)) end_session(CalibrationStatus::Aborted);

  if (cal_status_ == CalibrationStatus::Running && !faulted && nmt_state_ == NodeState::PreOperational) {
    applied_ = calibration_output(s, now_us);
    limiter_ = Limiter::None;
    if (session_open_ && cal_status_ == CalibrationStatus::Running) {
      // Inside a session the host keeps serving the joints the procedure does not use (an
      // unbalanced pitch would fall while yaw looks for its index).
      const JointArray host = session_output(s);
      for (int j = 0; j < kJointCount; ++j) {
        const bool owned = cal_procedure_ == CalibrationProcedure::FindIndex ? j == cal_joint_ : ((cal_mask_ >> j) & 1u) != 0;
        if (!owned) applied_[j] = host[j];
      }
    }
  } else {
    if (cal_status_ == CalibrationStatus::Running) finish_calibration(CalibrationStatus::Aborted, 0);
    applied_ = session_open_ ? session_output(s) : limited_output(s);
  }
  // The drive regulates the sensor's reading: add the measured sensor offset so the motor gets
  // the current asked for. Zero stays zero (bridge off).
  JointArray drive{};
  for (int j = 0; j < kJointCount; ++j)
    drive[j] = applied_[j] == 0.0f ? 0.0f : applied_[j] + params_.f32(static_cast<std::uint16_t>(param::kCurrentOffset + j));
  hw_.apply_currents(drive);

  if (now_us >= next_heartbeat_us_) {
    send_heartbeat();
    next_heartbeat_us_ = now_us + 1000ull * params_.u32(param::kHeartbeatPeriod_ms);
  }
  if (hand_readout_ && session_open_ && now_us >= next_hand_us_) {
    next_hand_us_ = now_us + kHandSensorPeriod_us;
    const std::int32_t raw[3] = {s.roll_raw, s.jaw_raw, s.pedal_raw};
    for (std::uint8_t k = 0; k < 3; ++k)
      queue(CalibrationProgress{node_id_, CalibrationProcedure::HandSensors, CalibrationStatus::Running, 0, k, raw[k]});
  }
  if (nmt_state_ != NodeState::Stopped && now_us >= next_aux_us_) {
    next_aux_us_ = now_us + 1000ull * params_.u32(param::kAuxPeriod_ms);
    const HandReading hand = calibrated_hand(params_, s);
    queue(AuxState{node_id_, aux_counter_++, hand.pedal, s.estop_input, s.handle_button,
                   clampf(hand.roll_rad, -3.1416f, 3.1416f), clampf(hand.jaw_rad, 0, 3.1416f), clampf(s.bus_V, 0, 100)});
    JointArray measured{};
    for (int j = 0; j < kJointCount; ++j) measured[j] = clampf(s.current[j], -30, 30);
    const float t = clampf(s.board_temperature_degC, -40, 125);
    queue(CurrentState{node_id_, current_state_counter_++, static_cast<std::int8_t>(std::lround(t)), measured});
  }
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::check_faults(const HardwareSample& s, std::uint64_t now_us) {
  if (s.estop_input) raise(FaultCode::EmergencyStop, 0xFF, 1);
  if (faults_.latched() != FaultCode::None) return;
  if (enabled_ || session_open_) {
    const std::uint64_t silent_us = now_us - last_command_us_;
    // A host that negotiated 1.2 knows the session's watchdog; an older one keeps what it knew.
    const bool session_watchdog = session_open_ && negotiated_minor_ != 0xFF && negotiated_minor_ >= 2;
    const std::uint64_t timeout_us = session_watchdog ? kSessionWatchdog_us : params_.u32(param::kWatchdogTimeout_us);
    if (silent_us > timeout_us) {
      raise(FaultCode::CommandWatchdog, 0xFF, static_cast<std::int16_t>(silent_us / 1000 > 32767 ? 32767 : silent_us / 1000));
      return;
    }
  }
  const float overcurrent = params_.f32(param::kOvercurrentFactor);
  const float overspeed = params_.f32(param::kOverspeedFactor);
  for (int j = 0; j < kJointCount; ++j) {
    const auto jj = static_cast<std::uint16_t>(j);
    const auto joint = static_cast<std::uint8_t>(j);
    if (std::fabs(s.current[j]) > overcurrent * params_.f32(param::kMaxCurrent + jj))
      return raise(FaultCode::OverCurrent, joint, static_cast<std::int16_t>(clampf(s.current[j] * 1000, -32767, 32767)));
    if (std::fabs(s.velocity[j]) > overspeed * params_.f32(param::kMaxVelocity + jj))
      return raise(FaultCode::OverSpeed, joint, static_cast<std::int16_t>(clampf(s.velocity[j] * 1000, -32767, 32767)));
    const float lo = params_.f32(param::kJointMin + jj), hi = params_.f32(param::kJointMax + jj);
    const float margin = 0.1f * (hi - lo);  // beyond the soft range by this much: sensor or mechanics broke
    if (enabled_ && (s.position[j] < lo - margin || s.position[j] > hi + margin))
      return raise(FaultCode::JointRangeExceeded, joint, static_cast<std::int16_t>(clampf(s.position[j] * 1e4f, -32767, 32767)));
  }
  if (s.bus_V < params_.f32(param::kMinBus_V))
    return raise(FaultCode::UnderVoltage, 0xFF, static_cast<std::int16_t>(s.bus_V * 100));
  if (s.bus_V > params_.f32(param::kMaxBus_V))
    return raise(FaultCode::OverVoltage, 0xFF, static_cast<std::int16_t>(clampf(s.bus_V * 100, 0, 32767)));
  if (s.board_temperature_degC > params_.f32(param::kMaxBoardTemperature_degC))
    return raise(FaultCode::OverTemperature, 0xFF, static_cast<std::int16_t>(s.board_temperature_degC));
}

template <VESICA_NODE_HARDWARE Hw>
JointArray Node<Hw>::limited_output(const HardwareSample& s) {
  JointArray out{};
  if (faults_.latched() != FaultCode::None) { limiter_ = Limiter::Fault; return out; }
  if (!enabled_ || nmt_state_ != NodeState::Operational) { limiter_ = Limiter::Disabled; return out; }
  Limiter worst = Limiter::None;
  auto note = [&worst](Limiter l) { if (static_cast<std::uint8_t>(l) > static_cast<std::uint8_t>(worst)) worst = l; };
  for (int j = 0; j < kJointCount; ++j) {
    const auto jj = static_cast<std::uint16_t>(j);
    const float nm_per_A = params_.f32(param::kTorqueConstant + jj) * params_.f32(param::kGearRatio + jj);
    float amps = command_mode_ == CommandMode::JointTorque ? command_[j] / nm_per_A : command_[j];
    const float max_torque_amps = params_.f32(param::kMaxTorque + jj) / nm_per_A;
    if (std::fabs(amps) > max_torque_amps) { amps = std::copysign(max_torque_amps, amps); note(Limiter::Torque); }
    const float max_amps = params_.f32(param::kMaxCurrent + jj);
    if (std::fabs(amps) > max_amps) { amps = std::copysign(max_amps, amps); note(Limiter::Current); }
    // Beyond the speed limit, no current that accelerates further.
    const float v = s.velocity[j];
    if (std::fabs(v) > params_.f32(param::kMaxVelocity + jj) && amps * v > 0) { amps = 0; note(Limiter::Velocity); }
    // Outside the joint range, no current that pushes further out.
    if ((s.position[j] > params_.f32(param::kJointMax + jj) && amps > 0) ||
        (s.position[j] < params_.f32(param::kJointMin + jj) && amps < 0)) { amps = 0; note(Limiter::JointRange); }
    out[j] = amps;
  }
  limiter_ = worst;
  return out;
}

template <VESICA_NODE_HARDWARE Hw>
JointArray Node<Hw>::session_output(const HardwareSample& s) {
  // Host-driven calibration: the masked joints get the host's current within the session's
  // bound; the session's speed bound holds (no current that speeds a joint up beyond it). No
  // joint-range limit: the range is what is being measured.
  JointArray out{};
  Limiter worst = Limiter::None;
  for (int j = 0; j < kJointCount; ++j) {
    if (!(session_mask_ & (1u << j))) continue;
    const auto jj = static_cast<std::uint16_t>(j);
    const float nm_per_A = params_.f32(param::kTorqueConstant + jj) * params_.f32(param::kGearRatio + jj);
    float amps = command_mode_ == CommandMode::JointTorque ? command_[j] / nm_per_A : command_[j];
    const float bound = clampf(session_max_current_, 0, params_.f32(param::kMaxCurrent + jj));
    if (std::fabs(amps) > bound) { amps = std::copysign(bound, amps); worst = Limiter::Current; }
    const float v = s.velocity[j];
    if (std::fabs(v) > kSessionSpeedFraction * params_.f32(param::kMaxVelocity + jj) && amps * v > 0) {
      amps = 0;
      worst = Limiter::Velocity;
    }
    out[j] = amps;
  }
  limiter_ = worst;
  return out;
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::end_session(CalibrationStatus status) {
  session_open_ = false;
  hand_readout_ = false;
  command_ = JointArray{};
  applied_ = JointArray{};
  hw_.apply_currents(applied_);
  // Unsaved: whatever the host wrote during the session goes; the stored calibration is in force,
  // in this power-up's frame once homed.
  if (status != CalibrationStatus::Done) {
    reload_parameters();
    if (homed_ && has_home_offset_)
      for (int j = 0; j < kJointCount; ++j)
        params_.set_internal_f32(static_cast<std::uint16_t>(param::kPositionOffset + j), home_offset_[j]);
  }
  home_declared_in_session_ = false;
  queue(CalibrationProgress{node_id_, CalibrationProcedure::Session, status,
                            static_cast<std::uint8_t>(status == CalibrationStatus::Done ? 100 : 0), 0, 0});
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::declare_home() {
  homed_ = true;
  has_home_offset_ = true;
  home_declared_in_session_ = true;
  for (int j = 0; j < kJointCount; ++j)
    home_offset_[j] = params_.f32(static_cast<std::uint16_t>(param::kPositionOffset + j));
}

template <VESICA_NODE_HARDWARE Hw>
bool Node<Hw>::offsets_are_home() const {
  for (int j = 0; j < kJointCount; ++j)
    if (params_.f32(static_cast<std::uint16_t>(param::kPositionOffset + j)) != home_offset_[j]) return false;
  return true;
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::keep_home_after_save() {
  // Saved offsets that a host measured in this session (it declared them) are this power-up's
  // frame; others (a restored image) are another power-up's: the arm must be homed again.
  if (home_declared_in_session_) {
    declare_home();
  } else if (has_home_offset_ && !offsets_are_home()) {
    has_home_offset_ = false;
    homed_ = !homing_required();
  }
}

template <VESICA_NODE_HARDWARE Hw>
StorageResult Node<Hw>::load_parameters() {
  std::uint8_t buf[slot::kSize];
  SlotHeader headers[slot::kCount];
  for (int s = 0; s < slot::kCount; ++s) {
    slot_status_[s] = StorageResult::BadMagic;
    slot_generation_[s] = 0;
    if (!hw_.storage_read(slot::offset(s), buf, slot::kSize)) continue;
    SlotCheck c = check_slot(buf, slot::kSize);
    // Firmware before protocol 1.3 knew layout 1 only.
    if (c.status == StorageResult::Ok && max_minor_ < kLayout2Minor && c.layout > 1) c.status = StorageResult::BadVersion;
    slot_status_[s] = c.status;
    if (c.status != StorageResult::Ok) continue;
    ParameterStore scratch;  // a slot counts as valid only if its image loads too
    const StorageResult image = scratch.deserialize(buf + slot::kHeaderSize, c.size - slot::kHeaderSize - 4);
    if (image != StorageResult::Ok) {
      slot_status_[s] = image == StorageResult::BadMagic ? StorageResult::BadCrc : image;
      continue;
    }
    slot_generation_[s] = c.header.generation;
    headers[s] = c.header;
  }
  params_.restore_defaults();
  stored_layout_ = 0;
  active_slot_ = choose_boot_slot(slot_status_, slot_generation_);
  StorageResult result = StorageResult::BadMagic;
  if (active_slot_ >= 0 && hw_.storage_read(slot::offset(active_slot_), buf, slot::kSize) &&
      params_.deserialize(buf + slot::kHeaderSize, slot::kSize - slot::kHeaderSize, &stored_layout_) ==
          StorageResult::Ok) {
    params_.set_internal(param::kCalibrationDate_s, headers[active_slot_].date_s);
    params_.set_internal(param::kCalibrationToolVersion, headers[active_slot_].tool_version);
    result = StorageResult::Ok;
  } else {
    active_slot_ = -1;
    stored_layout_ = 0;
    params_.restore_defaults();
    // A board saved before protocol 1.1 holds one bare parameter image at offset 0: slot A, generation 0.
    std::uint8_t legacy[ParameterStore::kLayout1ImageSize];
    if (hw_.storage_read(0, legacy, sizeof legacy) && slot_detail::get_u32(legacy) == ParameterStore::kMagic) {
      const StorageResult r = params_.deserialize(legacy, sizeof legacy, &stored_layout_);
      slot_status_[0] = r;
      if (r == StorageResult::Ok) active_slot_ = 0;
      else params_.restore_defaults();
    }
    if (active_slot_ == 0) result = StorageResult::Ok;
    for (int s = 0; s < slot::kCount && result != StorageResult::Ok; ++s)
      if (slot_status_[s] != StorageResult::BadMagic) result = slot_status_[s];
  }
  sync_slot_parameters();
  return result;
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::reload_parameters() {
  load_parameters();
  params_.set_internal(param::kSerial, serial_);
  params_.set_internal(param::kNodeId, node_id_);
  sync_fault_parameters();
}

template <VESICA_NODE_HARDWARE Hw>
bool Node<Hw>::save_parameters() {
  // Never the newest valid slot: a write cut at any byte leaves that one as it was.
  const int target = save_target(slot_status_, slot_generation_);
  std::uint32_t generation = 0;
  for (int s = 0; s < slot::kCount; ++s)
    if (slot_status_[s] == StorageResult::Ok && slot_generation_[s] > generation) generation = slot_generation_[s];
  const SlotHeader header{generation + 1, params_.u32(param::kCalibrationDate_s),
                          params_.u32(param::kCalibrationToolVersion), serial_};
  const std::uint16_t layout = max_minor_ < kLayout2Minor ? 1 : ParameterStore::kLayoutVersion;
  std::uint8_t image[ParameterStore::kImageSize];
  std::uint8_t out[slot::kSize];
  const std::size_t image_size = params_.serialize(image, sizeof image, layout);
  const std::size_t size = image_size == 0 ? 0 : encode_slot(header, image, image_size, out, sizeof out);
  if (size == 0) return false;
  const bool written = hw_.storage_write(slot::offset(target), out, size);
  // What the storage holds now decides, whatever the write reported.
  std::uint8_t back[slot::kSize];
  const bool read = hw_.storage_read(slot::offset(target), back, size);
  bool same = read;
  for (std::size_t i = 0; same && i < size; ++i) same = back[i] == out[i];
  if (same) {
    slot_status_[target] = StorageResult::Ok;
    slot_generation_[target] = header.generation;
    active_slot_ = target;
    stored_layout_ = layout;
  } else {
    // Untouched (still the older valid slot) or spoilt: report what is there.
    const StorageResult now = read ? check_slot(back, size).status : StorageResult::BadMagic;
    if (now != StorageResult::Ok) {
      slot_status_[target] = now;
      slot_generation_[target] = 0;
    }
  }
  sync_slot_parameters();
  return written && same;
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::sync_slot_parameters() {
  params_.set_internal(param::kActiveSlot, active_slot_ < 0 ? slot::kNoSlot : static_cast<std::uint32_t>(active_slot_));
  params_.set_internal(param::kStoredLayout, active_slot_ < 0 ? 0u : stored_layout_);
  for (int s = 0; s < slot::kCount; ++s) {
    params_.set_internal(static_cast<std::uint16_t>(param::kSlotStatus + s), static_cast<std::uint32_t>(slot_status_[s]));
    params_.set_internal(static_cast<std::uint16_t>(param::kSlotGeneration + s), slot_generation_[s]);
  }
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::raise(FaultCode code, std::uint8_t joint, std::int16_t detail) {
  const FaultCode before = faults_.latched();
  if (before == code) return;  // a held condition is one fault, not one per tick
  faults_.raise(code, joint, detail);
  enabled_ = false;
  applied_ = JointArray{};
  hw_.apply_currents(applied_);  // zero torque now, not at the next tick
  sync_fault_parameters();
  if (before == FaultCode::None || before != code)
    queue(Emergency{node_id_, code, joint, static_cast<std::uint8_t>(faults_.count() > 255 ? 255 : faults_.count()), detail});
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::sync_fault_parameters() {
  params_.set_internal(param::kFaultHistoryCount, faults_.count());
  for (int k = 0; k < param::kFaultHistoryDepth; ++k)
    params_.set_internal(static_cast<std::uint16_t>(param::kFaultHistory + k), faults_.entry(k));
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::send_joint_state() {
  JointState js{node_id_, joint_state_counter_++, state(), enabled_, limiter_, {}};
  js.position[0] = clampf(position_[0], -3.1416f, 3.1416f);
  js.position[1] = clampf(position_[1], -3.1416f, 3.1416f);
  js.position[2] = clampf(position_[2], -0.1f, 0.32f);
  queue(js);
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::send_heartbeat() {
  // Only a host that negotiated 1.4 knows the flag (older decoders reject the bit).
  const bool flag = !homed_ && negotiated_minor_ != 0xFF && negotiated_minor_ >= kHomingMinor;
  queue(Heartbeat{node_id_, state(), enabled_, faults_.latched(), flag});
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::send_identity() {
  queue(Identity{node_id_, kProtocolMajor, 0, max_minor_, negotiated_minor_, serial_});
}

template <VESICA_NODE_HARDWARE Hw>
void Node<Hw>::queue(const Message& m) {
  CanFrame f;
  if (encode(m, f) != EncodeError::None) return;  // node-built messages are in range by construction
  if (tx_size_ == kTxQueueDepth) { ++tx_overflows_; return; }
  tx_[(tx_head_ + tx_size_) % kTxQueueDepth] = f;
  ++tx_size_;
}

template <VESICA_NODE_HARDWARE Hw>
bool Node<Hw>::pop_tx(CanFrame& out) {
  if (tx_size_ == 0) return false;
  out = tx_[tx_head_];
  tx_head_ = (tx_head_ + 1) % kTxQueueDepth;
  --tx_size_;
  return true;
}

}  // namespace vesica::fp
