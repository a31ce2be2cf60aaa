#include "device/calibration/calibration_link.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <variant>

#include "device/calibration/calibration_abort.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::device::calibration {
namespace {

double Seconds(fp::Nanoseconds t) { return 1e-9 * static_cast<double>(t.count()); }

std::string AbortText(std::uint32_t code) {
  switch (static_cast<fp::AbortCode>(code)) {
    case fp::AbortCode::CommandInvalid:
      return "command invalid";
    case fp::AbortCode::ReadOnly:
      return "read-only parameter";
    case fp::AbortCode::NoSuchParameter:
      return "no such parameter";
    case fp::AbortCode::TypeMismatch:
      return "type mismatch";
    case fp::AbortCode::ValueTooHigh:
      return "value too high";
    case fp::AbortCode::ValueTooLow:
      return "value too low";
    case fp::AbortCode::StorageFailed:
      return "storage failed";
    case fp::AbortCode::WrongState:
      return "not in this state";
    default:
      return "abort code " + std::to_string(code);
  }
}

}  // namespace

CalibrationLink::CalibrationLink(fp::Transport& transport, Waiter wait, const CalibrationLinkConfig& config)
    : transport_(transport), wait_(std::move(wait)), config_(config) {
  next_ = transport_.now();
}

double CalibrationLink::now_s() const { return Seconds(transport_.now()); }

void CalibrationLink::Send(const fp::Message& m) {
  fp::CanFrame f;
  if (fp::encode(m, f) != fp::EncodeError::None)
    throw CalibrationAbort(AbortReason::kRefused, "calibration: a request could not be encoded (value out of range)");
  transport_.send(f, transport_.now() + config_.send_deadline);  // a lost frame shows as a missing answer
}

void CalibrationLink::WaitPeriod() {
  // A host that fell behind (it stalled) restarts its grid from now instead of bursting commands to
  // catch up, and still gives the node a period to answer before it judges the link: its own
  // stall is not a lost arm.
  next_ += config_.period;
  if (next_ <= transport_.now()) next_ = transport_.now() + config_.period;
  wait_(next_);
}

void CalibrationLink::ReceiveAll() {
  fp::TimedFrame rx;
  while (transport_.receive(rx)) {
    fp::Message m;
    if (fp::decode(rx.frame, m) != fp::DecodeError::None) continue;
    if (fp::spec_of(fp::kind_of(m)).per_node && fp::node_of(m) != config_.node_id) continue;
    Handle(m, rx.timestamp);
  }
}

void CalibrationLink::Handle(const fp::Message& m, fp::Nanoseconds t) {
  if (const auto* js = std::get_if<fp::JointState>(&m)) {
    for (int j = 0; j < 3; ++j) sample_.position[j] = js->position[j];
    sample_.limiter = js->limiter;
    sample_.t_s = Seconds(t);
    last_state_ = t;
    node_state_ = js->state;
  } else if (const auto* cs = std::get_if<fp::CurrentState>(&m)) {
    for (int j = 0; j < 3; ++j) sample_.current_A[j] = cs->current[j];
  } else if (const auto* hb = std::get_if<fp::Heartbeat>(&m)) {
    node_state_ = hb->state;
    heartbeat_seen_ = true;
    node_fault_ = hb->latched_fault;
    node_not_homed_ = hb->not_homed;
  } else if (const auto* em = std::get_if<fp::Emergency>(&m)) {
    node_fault_ = em->fault;
  } else if (const auto* id = std::get_if<fp::Identity>(&m)) {
    identity_ =
        NodeIdentity{id->node, id->protocol_major, id->min_minor, id->max_minor, id->negotiated_minor, id->serial};
    identity_seen_ = true;
  } else if (const auto* pr = std::get_if<fp::ParameterResponse>(&m)) {
    response_ = *pr;
    response_seen_ = true;
  } else if (const auto* hs = std::get_if<fp::CalibrationProgress>(&m);
             hs && hs->procedure == fp::CalibrationProcedure::HandSensors &&
             hs->status == fp::CalibrationStatus::Running) {
    if (hs->joint < 3) {  // the readout's stream, not a procedure's progress
      hand_raw_[hs->joint] = hs->result;
      hand_raw_t_s_[hs->joint] = Seconds(t);
    }
  } else if (const auto* cp = std::get_if<fp::CalibrationProgress>(&m)) {
    progress_ = *cp;
    progress_seen_ = true;
    if (cp->procedure == fp::CalibrationProcedure::Session && cp->status != fp::CalibrationStatus::Running)
      session_open_ = false;
  }
}

void CalibrationLink::CheckStop() {
  // Order matters for the message: what the node says it did comes before what we only infer.
  // Faults stop a calibration; outside one (info, reading parameters) they are only reported.
  if (watch_faults_ && node_fault_ == fp::FaultCode::EmergencyStop)
    throw CalibrationAbort(AbortReason::kEmergencyStop,
                           "node " + std::to_string(config_.node_id) +
                               ": emergency stop; the arm is disabled, the stored calibration is in force");
  if (watch_faults_ && node_fault_ != fp::FaultCode::None)
    throw CalibrationAbort(AbortReason::kNodeFault, "node " + std::to_string(config_.node_id) + " latched fault " +
                                                        fp::to_string(node_fault_) +
                                                        "; the arm is disabled, the stored calibration is in force");
  if (abort_requested_)
    throw CalibrationAbort(AbortReason::kAbortRequested,
                           "calibration aborted by the user; the stored calibration is in force");
  if (last_state_.count() >= 0 && transport_.now() - last_state_ > config_.loss_timeout)
    throw CalibrationAbort(
        AbortReason::kLinkLost,
        "node " + std::to_string(config_.node_id) + ": no joint state for " +
            std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(config_.loss_timeout).count()) +
            " ms (link lost); the node's watchdog disables the arm");
}

const LinkSample& CalibrationLink::Cycle(const std::array<double, 3>& amps) {
  if (session_open_) {
    fp::CurrentCommand c{config_.node_id, command_counter_++, fp::CommandMode::MotorCurrent, {}};
    for (int j = 0; j < 3; ++j) c.value[j] = static_cast<float>(std::clamp(amps[j], -30.0, 30.0));
    last_amps_ = amps;
    Send(c);
  } else {
    Send(fp::Sync{sync_counter_++});
  }
  WaitPeriod();
  ReceiveAll();
  // A session the node ended by itself (fault, watchdog) is reported by the fault above it.
  CheckStop();
  return sample_;
}

fp::ParameterResponse CalibrationLink::Ask(const fp::ParameterRequest& request) {
  response_seen_ = false;
  Send(request);
  const fp::Nanoseconds until = transport_.now() + config_.reply_timeout;
  while (true) {
    Cycle(last_amps_);  // keep commanding (and feeding the watchdog) while waiting
    if (response_seen_ && response_.index == request.index && response_.op == request.op) break;
    if (transport_.now() > until)
      throw CalibrationAbort(
          AbortReason::kNoAnswer, "node " + std::to_string(config_.node_id) + " did not answer parameter 0x" + [&] {
            char b[8];
            std::snprintf(b, sizeof b, "%04X", request.index);
            return std::string(b);
          }());
  }
  if (response_.aborted) {
    char b[8];
    std::snprintf(b, sizeof b, "%04X", request.index);
    throw CalibrationAbort(AbortReason::kRefused, "node " + std::to_string(config_.node_id) + " refused parameter 0x" +
                                                      b + ": " + AbortText(response_.raw_value));
  }
  return response_;
}

NodeIdentity CalibrationLink::Connect() {
  ReceiveAll();  // a boot-up Identity already waiting (negotiated nothing yet) is not the answer
  identity_seen_ = false;
  Send(fp::Hello{config_.node_id, fp::kProtocolMajor, fp::kProtocolMinor});
  fp::Nanoseconds until = transport_.now() + config_.reply_timeout;
  bool hello_repeated = false;
  while (transport_.now() <= until) {
    WaitPeriod();
    ReceiveAll();
    if (abort_requested_) CheckStop();
    if (!identity_seen_) continue;
    // An Identity that negotiated nothing is the node's boot-up announcement overtaking our Hello
    // (a node that started, or rebooted, just now): ask once more before calling it too old.
    if (identity_.negotiated_minor == 0xFF && !hello_repeated) {
      hello_repeated = true;
      identity_seen_ = false;
      Send(fp::Hello{config_.node_id, fp::kProtocolMajor, fp::kProtocolMinor});
      until = transport_.now() + config_.reply_timeout;
      continue;
    }
    break;
  }
  if (!identity_seen_)
    throw CalibrationAbort(AbortReason::kNoAnswer, "no answer from node " + std::to_string(config_.node_id) +
                                                       " (is the arm powered and on this bus?)");
  if (identity_.protocol_major != fp::kProtocolMajor || identity_.negotiated_minor == 0xFF)
    throw CalibrationAbort(AbortReason::kProtocolTooOld,
                           "node " + std::to_string(config_.node_id) + " speaks protocol " +
                               std::to_string(identity_.protocol_major) + ".x; this tool speaks " +
                               std::to_string(fp::kProtocolMajor) + "." + std::to_string(fp::kProtocolMinor));
  if (identity_.max_minor < kCalibrationMinor)
    throw CalibrationAbort(AbortReason::kProtocolTooOld,
                           "node " + std::to_string(config_.node_id) + " speaks protocol " +
                               std::to_string(identity_.protocol_major) + "." + std::to_string(identity_.max_minor) +
                               "; calibration needs " + std::to_string(fp::kProtocolMajor) + "." +
                               std::to_string(kCalibrationMinor) + " (update the arm's firmware); nothing was changed");
  return identity_;
}

void CalibrationLink::ClearFault() {
  AwaitHeartbeat();  // it says whether a fault is latched
  if (node_fault_ == fp::FaultCode::None && node_state_ != fp::NodeState::Fault) return;
  Send(fp::Control{config_.node_id, control_counter_++, fp::ControlCommand::FaultReset});
  node_fault_ = fp::FaultCode::None;
  for (int i = 0; i < 20; ++i) {  // the acknowledging heartbeat
    WaitPeriod();
    ReceiveAll();
  }
  if (node_fault_ != fp::FaultCode::None)
    throw CalibrationAbort(AbortReason::kNodeFault, "node " + std::to_string(config_.node_id) + " keeps fault " +
                                                        fp::to_string(node_fault_) + " (is the E-stop released?)");
}

float CalibrationLink::ReadF32(std::uint16_t index) { return fp::bits_f32(Read(index).raw_value); }

fp::ParameterResponse CalibrationLink::Read(std::uint16_t index) {
  return Ask(fp::ParameterRequest{config_.node_id, fp::ParameterOp::Read, fp::ParameterType::None, index, 0});
}
void CalibrationLink::WriteU32(std::uint16_t index, std::uint32_t value) {
  Ask(fp::ParameterRequest{config_.node_id, fp::ParameterOp::Write, fp::ParameterType::U32, index, value});
}
void CalibrationLink::WriteI32(std::uint16_t index, std::int32_t value) {
  Ask(fp::ParameterRequest{config_.node_id, fp::ParameterOp::Write, fp::ParameterType::I32, index,
                           static_cast<std::uint32_t>(value)});
}
void CalibrationLink::WriteF32(std::uint16_t index, float value) {
  Ask(fp::ParameterRequest{config_.node_id, fp::ParameterOp::Write, fp::ParameterType::F32, index,
                           fp::f32_bits(value)});
}

void CalibrationLink::Save() {
  Ask(fp::ParameterRequest{config_.node_id, fp::ParameterOp::Save, fp::ParameterType::None, 0, 0});
  for (int i = 0; i < 20 && session_open_; ++i) Cycle(last_amps_);  // the session's "done"
  watch_faults_ = false;
}

void CalibrationLink::AwaitHeartbeat() {
  heartbeat_seen_ = false;
  for (int i = 0; i < 300 && !heartbeat_seen_; ++i) Cycle(last_amps_);
}

void CalibrationLink::BeginSession(std::uint8_t joint_mask, double max_current_A) {
  Send(fp::Nmt{fp::NmtCommand::EnterPreOperational, config_.node_id});
  progress_seen_ = false;
  Send(fp::CalibrationCommand{config_.node_id, fp::CalibrationProcedure::Session, joint_mask,
                              static_cast<float>(max_current_A)});
  const fp::Nanoseconds until = transport_.now() + config_.reply_timeout;
  while (true) {
    WaitPeriod();
    ReceiveAll();
    CheckStop();
    if (progress_seen_ && progress_.procedure == fp::CalibrationProcedure::Session) break;
    if (transport_.now() > until)
      throw CalibrationAbort(AbortReason::kNoAnswer,
                             "node " + std::to_string(config_.node_id) + " did not open a calibration session");
  }
  if (progress_.status != fp::CalibrationStatus::Running)
    throw CalibrationAbort(AbortReason::kRefused,
                           "node " + std::to_string(config_.node_id) +
                               " refused the calibration session (enabled, faulted or not pre-operational)");
  session_open_ = true;
  watch_faults_ = true;
  last_amps_ = {};
  last_state_ = transport_.now();  // loss is counted from here
}

void CalibrationLink::AbortSession() noexcept {
  try {
    Send(fp::CalibrationCommand{config_.node_id, fp::CalibrationProcedure::Abort, 0, 0.0f});
  } catch (...) {
  }
  session_open_ = false;
  watch_faults_ = false;
  last_amps_ = {};
}

void CalibrationLink::DeclareHome() {
  RunNodeProcedure(fp::CalibrationProcedure::Home, 0b111, 0.0, Seconds(config_.reply_timeout),
                   [this] { return last_amps_; });
}

void CalibrationLink::StartHandSensorReadout(const std::string& what) {
  if (identity_.negotiated_minor == 0xFF || identity_.negotiated_minor < 2)
    throw CalibrationAbort(
        AbortReason::kProtocolTooOld,
        "node " + std::to_string(config_.node_id) + " speaks protocol " + std::to_string(identity_.protocol_major) +
            "." +
            std::to_string(identity_.negotiated_minor == 0xFF ? identity_.max_minor : identity_.negotiated_minor) +
            " with this tool; " + what + " need 1.2 (update the arm's firmware); nothing was changed");
  progress_seen_ = false;
  hand_raw_t_s_ = {-1.0, -1.0, -1.0};
  Send(fp::CalibrationCommand{config_.node_id, fp::CalibrationProcedure::HandSensors, 0b111, 0.0f});
  const double until = now_s() + Seconds(config_.reply_timeout);
  while (hand_raw_t_s_[0] < 0 || hand_raw_t_s_[1] < 0 || hand_raw_t_s_[2] < 0) {
    Cycle(last_amps_);
    if (progress_seen_ && progress_.procedure == fp::CalibrationProcedure::HandSensors &&
        progress_.status == fp::CalibrationStatus::Failed)
      throw CalibrationAbort(AbortReason::kRefused,
                             "node " + std::to_string(config_.node_id) + " refused the hand-sensor readout");
    if (now_s() > until)
      throw CalibrationAbort(AbortReason::kNoAnswer,
                             "node " + std::to_string(config_.node_id) + " did not report its hand sensors");
  }
}

std::int32_t CalibrationLink::RunNodeProcedure(fp::CalibrationProcedure procedure, std::uint8_t joint_mask,
                                               double max_current_A, double timeout_s,
                                               const std::function<std::array<double, 3>()>& command) {
  progress_seen_ = false;
  Send(fp::CalibrationCommand{config_.node_id, procedure, joint_mask, static_cast<float>(max_current_A)});
  const double until = now_s() + timeout_s;
  while (true) {
    Cycle(command());
    if (progress_seen_ && progress_.procedure == procedure && progress_.status != fp::CalibrationStatus::Running) break;
    if (now_s() > until)
      throw CalibrationAbort(AbortReason::kNoAnswer,
                             "node " + std::to_string(config_.node_id) + ": calibration procedure " +
                                 std::to_string(static_cast<int>(procedure)) + " did not finish");
  }
  if (progress_.status != fp::CalibrationStatus::Done)
    throw CalibrationAbort(AbortReason::kMeasurement,
                           "node " + std::to_string(config_.node_id) + ": calibration procedure " +
                               std::to_string(static_cast<int>(procedure)) + " " +
                               (progress_.status == fp::CalibrationStatus::Failed ? "failed" : "was aborted") +
                               " on joint " + std::to_string(progress_.joint));
  return progress_.result;
}

}  // namespace vesica::device::calibration
