// Which field carries which enumeration; the names of the enumerations the codec does not name.
#include "firmware_protocol/wireshark/value_names.h"

#include "firmware_protocol/codec/protocol_enums.h"
#include "firmware_protocol/wireshark/field_bits.h"

namespace vesica::fp {
namespace {

namespace F = fields;

const char* name(NmtCommand c) {
  switch (c) {
    case NmtCommand::Start: return "start";
    case NmtCommand::Stop: return "stop";
    case NmtCommand::EnterPreOperational: return "enter_pre_operational";
    case NmtCommand::ResetNode: return "reset_node";
    case NmtCommand::ResetCommunication: return "reset_communication";
  }
  return nullptr;
}
const char* name(ControlCommand c) {
  switch (c) {
    case ControlCommand::Enable: return "enable";
    case ControlCommand::Disable: return "disable";
    case ControlCommand::FaultReset: return "fault_reset";
  }
  return nullptr;
}
const char* name(CommandMode m) {
  switch (m) {
    case CommandMode::MotorCurrent: return "motor_current";
    case CommandMode::JointTorque: return "joint_torque";
  }
  return nullptr;
}
const char* name(ParameterOp op) {
  switch (op) {
    case ParameterOp::Read: return "read";
    case ParameterOp::Write: return "write";
    case ParameterOp::Save: return "save";
    case ParameterOp::RestoreDefaults: return "restore_defaults";
  }
  return nullptr;
}
const char* name(ParameterType t) {
  switch (t) {
    case ParameterType::None: return "none";
    case ParameterType::U32: return "u32";
    case ParameterType::I32: return "i32";
    case ParameterType::F32: return "f32";
  }
  return nullptr;
}
const char* name(CalibrationProcedure p) {
  switch (p) {
    case CalibrationProcedure::Abort: return "abort";
    case CalibrationProcedure::FindIndex: return "find_index";
    case CalibrationProcedure::CurrentOffset: return "current_offset";
    case CalibrationProcedure::Session: return "session";
    case CalibrationProcedure::HandSensors: return "hand_sensors";
    case CalibrationProcedure::Home: return "home";
  }
  return nullptr;
}
const char* name(CalibrationStatus s) {
  switch (s) {
    case CalibrationStatus::Idle: return "idle";
    case CalibrationStatus::Running: return "running";
    case CalibrationStatus::Done: return "done";
    case CalibrationStatus::Failed: return "failed";
    case CalibrationStatus::Aborted: return "aborted";
  }
  return nullptr;
}
// The codec's own names; "?" marks a value outside the enumeration.
const char* name(NodeState s) { return to_string(s); }
const char* name(Limiter l) { return to_string(l); }
const char* name(FaultCode f) { return to_string(f); }

template <typename Enum>
FieldValueNames names_of(const FieldSpec& f) {
  FieldValueNames out{&f, {}};
  for (std::int64_t raw = raw_min(f); raw <= raw_max(f); ++raw) {
    const char* n = name(static_cast<Enum>(raw));
    if (n && std::string(n) != "?") out.names.emplace_back(raw, n);
  }
  return out;
}

}  // namespace

std::vector<FieldValueNames> field_value_names() {
  return {
      names_of<NmtCommand>(F::Nmt::command),
      names_of<FaultCode>(F::Emergency::fault),
      names_of<NodeState>(F::JointState::state),
      names_of<Limiter>(F::JointState::limiter),
      names_of<CommandMode>(F::CurrentCommand::mode),
      names_of<ControlCommand>(F::Control::command),
      names_of<CalibrationProcedure>(F::CalibrationCommand::procedure),
      names_of<CalibrationProcedure>(F::CalibrationProgress::procedure),
      names_of<CalibrationStatus>(F::CalibrationProgress::status),
      names_of<ParameterOp>(F::ParameterRequest::op),
      names_of<ParameterType>(F::ParameterRequest::type),
      names_of<ParameterOp>(F::ParameterResponse::op),
      names_of<ParameterType>(F::ParameterResponse::type),
      names_of<NodeState>(F::Heartbeat::state),
      names_of<FaultCode>(F::Heartbeat::latched_fault),
  };
}

}  // namespace vesica::fp
