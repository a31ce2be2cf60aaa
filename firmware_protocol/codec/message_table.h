// The one definition of the Vesica CAN wire format: every message's identifier, length, rate and
// every field's offset, width, scaling, unit and valid range.
// Use: the codec (codec.cpp) packs and checks fields only through these descriptors; the markdown
// tables in docs/protocol.md are generated from them (protocol_table_markdown.h) and a test checks
// the document against this file. Change the wire format here and nowhere else.
// Freestanding C++17.
#pragma once

#include <cstddef>
#include <cstdint>

namespace vesica::fp {

// Index of each message in the Message variant (messages.h); kMessageSpecs is in the same order.
enum class MessageKind : std::uint8_t {
  Nmt, EStop, Sync, Emergency, JointState, CurrentCommand, AuxState, Control, CurrentState,
  CalibrationCommand, CalibrationProgress, Identity, Hello, ParameterRequest, ParameterResponse,
  Heartbeat
};
inline constexpr std::size_t kMessageKindCount = 16;

enum class Direction : std::uint8_t { HostToNode, NodeToHost, Broadcast };

struct MessageSpec {
  MessageKind kind;
  const char* name;
  std::uint16_t base_id;   // 11-bit id; per-node messages add the node id (1..127)
  bool per_node;
  std::uint8_t length;     // payload bytes, exact (a frame of any other length is rejected)
  Direction direction;
  std::uint16_t rate_hz;   // nominal rate in operation; 0 = on event only
  bool has_counter;        // byte 0 (or 1 for Control) is a sequence counter checked by receivers
  const char* purpose;
};

// CANopen-style identifier plan: id = function code << 7 | node id. NMT 0x000, SYNC 0x080,
// EMCY 0x080+n, SDO-like 0x580/0x600+n and heartbeat 0x700+n keep their CiA 301 places.
inline constexpr MessageSpec kMessageSpecs[kMessageKindCount] = {
  {MessageKind::Nmt, "Nmt", 0x000, false, 2, Direction::HostToNode, 0, false, "NMT state command (CiA 301)"},
  {MessageKind::EStop, "EStop", 0x001, false, 2, Direction::Broadcast, 0, false, "emergency stop, every node zeroes torque and latches"},
  {MessageKind::Sync, "Sync", 0x080, false, 1, Direction::HostToNode, 0, true, "sample request; nodes answer JointState"},
  {MessageKind::Emergency, "Emergency", 0x080, true, 8, Direction::NodeToHost, 0, false, "fault raised or reset (CiA 301 EMCY layout)"},
  {MessageKind::JointState, "JointState", 0x180, true, 8, Direction::NodeToHost, 1000, true, "joint positions, node state, active limiter"},
  {MessageKind::CurrentCommand, "CurrentCommand", 0x200, true, 8, Direction::HostToNode, 1000, true, "motor current or joint torque command; feeds the watchdog"},
  {MessageKind::AuxState, "AuxState", 0x280, true, 8, Direction::NodeToHost, 100, true, "roll, jaw, pedal, buttons, bus voltage"},
  {MessageKind::Control, "Control", 0x300, true, 2, Direction::HostToNode, 0, true, "enable, disable, fault reset"},
  {MessageKind::CurrentState, "CurrentState", 0x380, true, 8, Direction::NodeToHost, 100, true, "measured motor currents, board temperature"},
  {MessageKind::CalibrationCommand, "CalibrationCommand", 0x400, true, 4, Direction::HostToNode, 0, false, "start or abort a calibration procedure"},
  {MessageKind::CalibrationProgress, "CalibrationProgress", 0x480, true, 8, Direction::NodeToHost, 10, false, "calibration progress and result"},
  {MessageKind::Identity, "Identity", 0x500, true, 8, Direction::NodeToHost, 0, false, "protocol versions supported/negotiated, serial"},
  {MessageKind::Hello, "Hello", 0x680, true, 2, Direction::HostToNode, 0, false, "host protocol version; starts negotiation"},
  {MessageKind::ParameterRequest, "ParameterRequest", 0x600, true, 8, Direction::HostToNode, 0, false, "typed parameter read/write/save/restore"},
  {MessageKind::ParameterResponse, "ParameterResponse", 0x580, true, 8, Direction::NodeToHost, 0, false, "parameter value or abort code"},
  {MessageKind::Heartbeat, "Heartbeat", 0x700, true, 3, Direction::NodeToHost, 10, false, "node state (byte 0 = CANopen heartbeat)"},
};

constexpr const MessageSpec& spec_of(MessageKind k) { return kMessageSpecs[static_cast<std::size_t>(k)]; }

enum class WireType : std::uint8_t { U8, I8, U16, I16, U32, I32 };

// One field: `bit_width` 0 means the whole integer; otherwise an unsigned bit field inside a U8.
// Numeric fields: SI value = raw * lsb; valid SI range [min, max] (raw range = round(min/lsb) ..
// round(max/lsb)). Enumerations and counters have lsb 1 and unit "".
struct FieldSpec {
  MessageKind message;
  const char* name;
  std::uint8_t offset;      // byte offset, little-endian
  WireType type;
  std::uint8_t bit_offset;  // for bit fields
  std::uint8_t bit_width;   // 0 = whole field
  double lsb;               // SI units per count
  const char* unit;
  double min;
  double max;
};

constexpr double kPiRange = 3.1416;  // 31416 * 1e-4 rad: a full turn each way fits an i16

// Fields, grouped by message; the codec names them as fields::<Message>::<field>.
namespace fields {
#define VESICA_FIELD(msg, name, ...) inline constexpr FieldSpec name{MessageKind::msg, #name, __VA_ARGS__}
namespace Nmt {
VESICA_FIELD(Nmt, command, 0, WireType::U8, 0, 0, 1, "", 1, 130);
VESICA_FIELD(Nmt, target_node, 1, WireType::U8, 0, 0, 1, "", 0, 127);
}  // namespace Nmt
namespace EStop {
VESICA_FIELD(EStop, magic, 0, WireType::U8, 0, 0, 1, "", 0xE5, 0xE5);
VESICA_FIELD(EStop, source_node, 1, WireType::U8, 0, 0, 1, "", 0, 127);
}  // namespace EStop
namespace Sync {
VESICA_FIELD(Sync, counter, 0, WireType::U8, 0, 0, 1, "", 0, 255);
}  // namespace Sync
namespace Emergency {
VESICA_FIELD(Emergency, error_code, 0, WireType::U16, 0, 0, 1, "", 0, 65535);
VESICA_FIELD(Emergency, error_register, 2, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(Emergency, fault, 3, WireType::U8, 0, 0, 1, "", 0, 10);
VESICA_FIELD(Emergency, joint, 4, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(Emergency, history_count, 5, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(Emergency, detail, 6, WireType::I16, 0, 0, 1, "", -32768, 32767);
}  // namespace Emergency
namespace JointState {
VESICA_FIELD(JointState, counter, 0, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(JointState, state, 1, WireType::U8, 0, 3, 1, "", 0, 4);
VESICA_FIELD(JointState, enabled, 1, WireType::U8, 3, 1, 1, "", 0, 1);
VESICA_FIELD(JointState, limiter, 1, WireType::U8, 4, 4, 1, "", 0, 6);
VESICA_FIELD(JointState, yaw, 2, WireType::I16, 0, 0, 1e-4, "rad", -kPiRange, kPiRange);
VESICA_FIELD(JointState, pitch, 4, WireType::I16, 0, 0, 1e-4, "rad", -kPiRange, kPiRange);
VESICA_FIELD(JointState, insertion, 6, WireType::I16, 0, 0, 1e-5, "m", -0.1, 0.32);
}  // namespace JointState
namespace CurrentCommand {
VESICA_FIELD(CurrentCommand, counter, 0, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(CurrentCommand, mode, 1, WireType::U8, 0, 0, 1, "", 0, 1);
VESICA_FIELD(CurrentCommand, yaw, 2, WireType::I16, 0, 0, 1e-3, "A or N·m", -30, 30);
VESICA_FIELD(CurrentCommand, pitch, 4, WireType::I16, 0, 0, 1e-3, "A or N·m", -30, 30);
VESICA_FIELD(CurrentCommand, insertion, 6, WireType::I16, 0, 0, 1e-3, "A or N·m", -30, 30);
}  // namespace CurrentCommand
namespace AuxState {
VESICA_FIELD(AuxState, counter, 0, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(AuxState, pedal, 1, WireType::U8, 0, 1, 1, "", 0, 1);
VESICA_FIELD(AuxState, estop_input, 1, WireType::U8, 1, 1, 1, "", 0, 1);
VESICA_FIELD(AuxState, handle_button, 1, WireType::U8, 2, 1, 1, "", 0, 1);
VESICA_FIELD(AuxState, roll, 2, WireType::I16, 0, 0, 1e-4, "rad", -kPiRange, kPiRange);
VESICA_FIELD(AuxState, jaw, 4, WireType::U16, 0, 0, 1e-4, "rad", 0, kPiRange);
VESICA_FIELD(AuxState, bus_voltage, 6, WireType::U16, 0, 0, 1e-2, "V", 0, 100);
}  // namespace AuxState
namespace Control {
VESICA_FIELD(Control, command, 0, WireType::U8, 0, 0, 1, "", 1, 3);
VESICA_FIELD(Control, counter, 1, WireType::U8, 0, 0, 1, "", 0, 255);
}  // namespace Control
namespace CurrentState {
VESICA_FIELD(CurrentState, counter, 0, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(CurrentState, board_temperature, 1, WireType::I8, 0, 0, 1, "degC", -40, 125);
VESICA_FIELD(CurrentState, yaw, 2, WireType::I16, 0, 0, 1e-3, "A", -30, 30);
VESICA_FIELD(CurrentState, pitch, 4, WireType::I16, 0, 0, 1e-3, "A", -30, 30);
VESICA_FIELD(CurrentState, insertion, 6, WireType::I16, 0, 0, 1e-3, "A", -30, 30);
}  // namespace CurrentState
namespace CalibrationCommand {
VESICA_FIELD(CalibrationCommand, procedure, 0, WireType::U8, 0, 0, 1, "", 0, 5);
VESICA_FIELD(CalibrationCommand, joint_mask, 1, WireType::U8, 0, 0, 1, "", 0, 7);
VESICA_FIELD(CalibrationCommand, max_current, 2, WireType::U16, 0, 0, 1e-3, "A", 0, 30);
}  // namespace CalibrationCommand
namespace CalibrationProgress {
VESICA_FIELD(CalibrationProgress, procedure, 0, WireType::U8, 0, 0, 1, "", 0, 5);
VESICA_FIELD(CalibrationProgress, status, 1, WireType::U8, 0, 0, 1, "", 0, 4);
VESICA_FIELD(CalibrationProgress, percent, 2, WireType::U8, 0, 0, 1, "%", 0, 100);
VESICA_FIELD(CalibrationProgress, joint, 3, WireType::U8, 0, 0, 1, "", 0, 2);
VESICA_FIELD(CalibrationProgress, result, 4, WireType::I32, 0, 0, 1, "", -2147483648.0, 2147483647.0);
}  // namespace CalibrationProgress
namespace Identity {
VESICA_FIELD(Identity, protocol_major, 0, WireType::U8, 0, 0, 1, "", 1, 255);
VESICA_FIELD(Identity, min_minor, 1, WireType::U8, 0, 0, 1, "", 0, 254);
VESICA_FIELD(Identity, max_minor, 2, WireType::U8, 0, 0, 1, "", 0, 254);
VESICA_FIELD(Identity, negotiated_minor, 3, WireType::U8, 0, 0, 1, "", 0, 255);
VESICA_FIELD(Identity, serial, 4, WireType::U32, 0, 0, 1, "", 0, 4294967295.0);
}  // namespace Identity
namespace Hello {
VESICA_FIELD(Hello, protocol_major, 0, WireType::U8, 0, 0, 1, "", 1, 255);
VESICA_FIELD(Hello, protocol_minor, 1, WireType::U8, 0, 0, 1, "", 0, 254);
}  // namespace Hello
namespace ParameterRequest {
VESICA_FIELD(ParameterRequest, op, 0, WireType::U8, 0, 0, 1, "", 1, 4);
VESICA_FIELD(ParameterRequest, type, 1, WireType::U8, 0, 0, 1, "", 0, 3);
VESICA_FIELD(ParameterRequest, index, 2, WireType::U16, 0, 0, 1, "", 0, 65535);
VESICA_FIELD(ParameterRequest, value, 4, WireType::U32, 0, 0, 1, "", 0, 4294967295.0);
}  // namespace ParameterRequest
namespace ParameterResponse {
VESICA_FIELD(ParameterResponse, op, 0, WireType::U8, 0, 7, 1, "", 1, 4);
VESICA_FIELD(ParameterResponse, aborted, 0, WireType::U8, 7, 1, 1, "", 0, 1);
VESICA_FIELD(ParameterResponse, type, 1, WireType::U8, 0, 0, 1, "", 0, 3);
VESICA_FIELD(ParameterResponse, index, 2, WireType::U16, 0, 0, 1, "", 0, 65535);
VESICA_FIELD(ParameterResponse, value, 4, WireType::U32, 0, 0, 1, "", 0, 4294967295.0);
}  // namespace ParameterResponse
namespace Heartbeat {
VESICA_FIELD(Heartbeat, canopen_state, 0, WireType::U8, 0, 0, 1, "", 0, 127);
VESICA_FIELD(Heartbeat, state, 1, WireType::U8, 0, 3, 1, "", 0, 4);
VESICA_FIELD(Heartbeat, enabled, 1, WireType::U8, 3, 1, 1, "", 0, 1);
VESICA_FIELD(Heartbeat, not_homed, 1, WireType::U8, 4, 1, 1, "", 0, 1);
VESICA_FIELD(Heartbeat, latched_fault, 2, WireType::U8, 0, 0, 1, "", 0, 10);
}  // namespace Heartbeat
#undef VESICA_FIELD
}  // namespace fields

// Every field, in message order, for the documentation table and the table self-checks.
inline constexpr const FieldSpec* kAllFields[] = {
  &fields::Nmt::command, &fields::Nmt::target_node,
  &fields::EStop::magic, &fields::EStop::source_node,
  &fields::Sync::counter,
  &fields::Emergency::error_code, &fields::Emergency::error_register, &fields::Emergency::fault,
  &fields::Emergency::joint, &fields::Emergency::history_count, &fields::Emergency::detail,
  &fields::JointState::counter, &fields::JointState::state, &fields::JointState::enabled,
  &fields::JointState::limiter, &fields::JointState::yaw, &fields::JointState::pitch,
  &fields::JointState::insertion,
  &fields::CurrentCommand::counter, &fields::CurrentCommand::mode, &fields::CurrentCommand::yaw,
  &fields::CurrentCommand::pitch, &fields::CurrentCommand::insertion,
  &fields::AuxState::counter, &fields::AuxState::pedal, &fields::AuxState::estop_input,
  &fields::AuxState::handle_button, &fields::AuxState::roll, &fields::AuxState::jaw,
  &fields::AuxState::bus_voltage,
  &fields::Control::command, &fields::Control::counter,
  &fields::CurrentState::counter, &fields::CurrentState::board_temperature,
  &fields::CurrentState::yaw, &fields::CurrentState::pitch, &fields::CurrentState::insertion,
  &fields::CalibrationCommand::procedure, &fields::CalibrationCommand::joint_mask,
  &fields::CalibrationCommand::max_current,
  &fields::CalibrationProgress::procedure, &fields::CalibrationProgress::status,
  &fields::CalibrationProgress::percent, &fields::CalibrationProgress::joint,
  &fields::CalibrationProgress::result,
  &fields::Identity::protocol_major, &fields::Identity::min_minor, &fields::Identity::max_minor,
  &fields::Identity::negotiated_minor, &fields::Identity::serial,
  &fields::Hello::protocol_major, &fields::Hello::protocol_minor,
  &fields::ParameterRequest::op, &fields::ParameterRequest::type, &fields::ParameterRequest::index,
  &fields::ParameterRequest::value,
  &fields::ParameterResponse::op, &fields::ParameterResponse::aborted, &fields::ParameterResponse::type,
  &fields::ParameterResponse::index, &fields::ParameterResponse::value,
  &fields::Heartbeat::canopen_state, &fields::Heartbeat::state, &fields::Heartbeat::enabled,
  &fields::Heartbeat::latched_fault, &fields::Heartbeat::not_homed,
};

constexpr std::uint8_t wire_size(WireType t) {
  switch (t) {
    case WireType::U8: case WireType::I8: return 1;
    case WireType::U16: case WireType::I16: return 2;
    case WireType::U32: case WireType::I32: return 4;
  }
  return 0;
}

}  // namespace vesica::fp
