// Codec: packs and checks every field only through the descriptors in message_table.h.
#include "firmware_protocol/codec/codec.h"

#include <cmath>

namespace vesica::fp {
namespace {

namespace F = fields;

constexpr std::int64_t round_to_raw(double si, double lsb) {
  const double x = si / lsb;
  return static_cast<std::int64_t>(x < 0 ? x - 0.5 : x + 0.5);
}
constexpr std::int64_t raw_min(const FieldSpec& f) { return round_to_raw(f.min, f.lsb); }
constexpr std::int64_t raw_max(const FieldSpec& f) { return round_to_raw(f.max, f.lsb); }

std::int64_t read_raw(const std::uint8_t* d, const FieldSpec& f) {
  std::uint32_t u = 0;
  const std::uint8_t n = wire_size(f.type);
  for (std::uint8_t i = 0; i < n; ++i) u |= static_cast<std::uint32_t>(d[f.offset + i]) << (8 * i);
  if (f.bit_width != 0) return (u >> f.bit_offset) & ((1u << f.bit_width) - 1u);
  switch (f.type) {
    case WireType::I8: return static_cast<std::int8_t>(u);
    case WireType::I16: return static_cast<std::int16_t>(u);
    case WireType::I32: return static_cast<std::int32_t>(u);
    default: return u;
  }
}

void write_raw(std::uint8_t* d, const FieldSpec& f, std::int64_t raw) {
  if (f.bit_width != 0) {
    const std::uint32_t mask = (1u << f.bit_width) - 1u;
    d[f.offset] = static_cast<std::uint8_t>(d[f.offset] | ((static_cast<std::uint32_t>(raw) & mask) << f.bit_offset));
    return;
  }
  const auto u = static_cast<std::uint32_t>(raw);
  for (std::uint8_t i = 0; i < wire_size(f.type); ++i) d[f.offset + i] = static_cast<std::uint8_t>(u >> (8 * i));
}

struct Writer {
  std::uint8_t* d;
  EncodeError error = EncodeError::None;
  void raw(const FieldSpec& f, std::int64_t r) {
    if (r < raw_min(f) || r > raw_max(f)) { error = EncodeError::OutOfRange; return; }
    write_raw(d, f, r);
  }
  void si(const FieldSpec& f, double v) {
    if (!std::isfinite(v)) { error = EncodeError::OutOfRange; return; }
    const double x = v / f.lsb;
    if (x < -4.0e9 || x > 4.0e9) { error = EncodeError::OutOfRange; return; }
    raw(f, static_cast<std::int64_t>(std::llround(x)));
  }
};

struct Reader {
  const std::uint8_t* d;
  DecodeError error = DecodeError::None;
  std::int64_t raw(const FieldSpec& f) {
    const std::int64_t r = read_raw(d, f);
    if (r < raw_min(f) || r > raw_max(f)) error = DecodeError::OutOfRange;
    return r;
  }
  float si(const FieldSpec& f) { return static_cast<float>(static_cast<double>(raw(f)) * f.lsb); }
  std::uint8_t u8(const FieldSpec& f) { return static_cast<std::uint8_t>(raw(f)); }
  bool flag(const FieldSpec& f) { return raw(f) != 0; }
};

bool valid_nmt(std::int64_t c) { return c == 0x01 || c == 0x02 || c == 0x80 || c == 0x81 || c == 0x82; }

EncodeError encode_payload(const Message& m, std::uint8_t* d) {
  Writer w{d};
  if (auto* p = std::get_if<Nmt>(&m)) {
    const auto c = static_cast<std::int64_t>(p->command);
    if (!valid_nmt(c)) return EncodeError::OutOfRange;
    w.raw(F::Nmt::command, c);
    w.raw(F::Nmt::target_node, p->target_node);
    return w.error;
  }
  if (auto* p = std::get_if<EStop>(&m)) {
    w.raw(F::EStop::magic, 0xE5);
    w.raw(F::EStop::source_node, p->source_node);
    return w.error;
  }
  if (auto* p = std::get_if<Sync>(&m)) {
    w.raw(F::Sync::counter, p->counter);
    return w.error;
  }
  if (auto* p = std::get_if<Emergency>(&m)) {
    w.raw(F::Emergency::error_code, emcy_error_code(p->fault));
    w.raw(F::Emergency::error_register, emcy_error_register(p->fault));
    w.raw(F::Emergency::fault, static_cast<std::int64_t>(p->fault));
    w.raw(F::Emergency::joint, p->joint);
    w.raw(F::Emergency::history_count, p->history_count);
    w.raw(F::Emergency::detail, p->detail);
    return w.error;
  }
  if (auto* p = std::get_if<JointState>(&m)) {
    w.raw(F::JointState::counter, p->counter);
    w.raw(F::JointState::state, static_cast<std::int64_t>(p->state));
    w.raw(F::JointState::enabled, p->enabled ? 1 : 0);
    w.raw(F::JointState::limiter, static_cast<std::int64_t>(p->limiter));
    w.si(F::JointState::yaw, p->position[0]);
    w.si(F::JointState::pitch, p->position[1]);
    w.si(F::JointState::insertion, p->position[2]);
    return w.error;
  }
  if (auto* p = std::get_if<CurrentCommand>(&m)) {
    w.raw(F::CurrentCommand::counter, p->counter);
    w.raw(F::CurrentCommand::mode, static_cast<std::int64_t>(p->mode));
    w.si(F::CurrentCommand::yaw, p->value[0]);
    w.si(F::CurrentCommand::pitch, p->value[1]);
    w.si(F::CurrentCommand::insertion, p->value[2]);
    return w.error;
  }
  if (auto* p = std::get_if<AuxState>(&m)) {
    w.raw(F::AuxState::counter, p->counter);
    w.raw(F::AuxState::pedal, p->pedal);
    w.raw(F::AuxState::estop_input, p->estop_input);
    w.raw(F::AuxState::handle_button, p->handle_button);
    w.si(F::AuxState::roll, p->roll_rad);
    w.si(F::AuxState::jaw, p->jaw_rad);
    w.si(F::AuxState::bus_voltage, p->bus_V);
    return w.error;
  }
  if (auto* p = std::get_if<Control>(&m)) {
    w.raw(F::Control::command, static_cast<std::int64_t>(p->command));
    w.raw(F::Control::counter, p->counter);
    return w.error;
  }
  if (auto* p = std::get_if<CurrentState>(&m)) {
    w.raw(F::CurrentState::counter, p->counter);
    w.raw(F::CurrentState::board_temperature, p->board_temperature_degC);
    w.si(F::CurrentState::yaw, p->current[0]);
    w.si(F::CurrentState::pitch, p->current[1]);
    w.si(F::CurrentState::insertion, p->current[2]);
    return w.error;
  }
  if (auto* p = std::get_if<CalibrationCommand>(&m)) {
    w.raw(F::CalibrationCommand::procedure, static_cast<std::int64_t>(p->procedure));
    w.raw(F::CalibrationCommand::joint_mask, p->joint_mask);
    w.si(F::CalibrationCommand::max_current, p->max_current);
    return w.error;
  }
  if (auto* p = std::get_if<CalibrationProgress>(&m)) {
    w.raw(F::CalibrationProgress::procedure, static_cast<std::int64_t>(p->procedure));
    w.raw(F::CalibrationProgress::status, static_cast<std::int64_t>(p->status));
    w.raw(F::CalibrationProgress::percent, p->percent);
    w.raw(F::CalibrationProgress::joint, p->joint);
    w.raw(F::CalibrationProgress::result, p->result);
    return w.error;
  }
  if (auto* p = std::get_if<Identity>(&m)) {
    w.raw(F::Identity::protocol_major, p->protocol_major);
    w.raw(F::Identity::min_minor, p->min_minor);
    w.raw(F::Identity::max_minor, p->max_minor);
    w.raw(F::Identity::negotiated_minor, p->negotiated_minor);
    w.raw(F::Identity::serial, p->serial);
    if (p->min_minor > p->max_minor) return EncodeError::OutOfRange;
    return w.error;
  }
  if (auto* p = std::get_if<Hello>(&m)) {
    w.raw(F::Hello::protocol_major, p->protocol_major);
    w.raw(F::Hello::protocol_minor, p->protocol_minor);
    return w.error;
  }
  if (auto* p = std::get_if<ParameterRequest>(&m)) {
    w.raw(F::ParameterRequest::op, static_cast<std::int64_t>(p->op));
    w.raw(F::ParameterRequest::type, static_cast<std::int64_t>(p->type));
    w.raw(F::ParameterRequest::index, p->index);
    w.raw(F::ParameterRequest::value, p->raw_value);
    return w.error;
  }
  if (auto* p = std::get_if<ParameterResponse>(&m)) {
    w.raw(F::ParameterResponse::op, static_cast<std::int64_t>(p->op));
    w.raw(F::ParameterResponse::aborted, p->aborted);
    w.raw(F::ParameterResponse::type, static_cast<std::int64_t>(p->type));
    w.raw(F::ParameterResponse::index, p->index);
    w.raw(F::ParameterResponse::value, p->raw_value);
    return w.error;
  }
  if (auto* p = std::get_if<Heartbeat>(&m)) {
    w.raw(F::Heartbeat::canopen_state, canopen_heartbeat_code(p->state));
    w.raw(F::Heartbeat::state, static_cast<std::int64_t>(p->state));
    w.raw(F::Heartbeat::enabled, p->enabled);
    w.raw(F::Heartbeat::latched_fault, static_cast<std::int64_t>(p->latched_fault));
    w.raw(F::Heartbeat::not_homed, p->not_homed);
  }
  return w.error;
}

DecodeError decode_payload(MessageKind kind, std::uint8_t node, const std::uint8_t* d, Message& out) {
  Reader r{d};
  switch (kind) {
    case MessageKind::Nmt: {
      const std::int64_t c = r.raw(F::Nmt::command);
      if (!valid_nmt(c)) return DecodeError::OutOfRange;
      out = Nmt{static_cast<NmtCommand>(c), r.u8(F::Nmt::target_node)};
      break;
    }
    case MessageKind::EStop:
      r.raw(F::EStop::magic);
      out = EStop{r.u8(F::EStop::source_node)};
      break;
    case MessageKind::Sync: out = Sync{r.u8(F::Sync::counter)}; break;
    case MessageKind::Emergency: {
      Emergency e{node, static_cast<FaultCode>(r.u8(F::Emergency::fault)), r.u8(F::Emergency::joint),
                  r.u8(F::Emergency::history_count), static_cast<std::int16_t>(r.raw(F::Emergency::detail))};
      if (r.error == DecodeError::None &&
          (r.raw(F::Emergency::error_code) != emcy_error_code(e.fault) ||
           r.raw(F::Emergency::error_register) != emcy_error_register(e.fault)))
        return DecodeError::Inconsistent;
      out = e;
      break;
    }
    case MessageKind::JointState:
      out = JointState{node, r.u8(F::JointState::counter), static_cast<NodeState>(r.u8(F::JointState::state)),
                       r.flag(F::JointState::enabled), static_cast<Limiter>(r.u8(F::JointState::limiter)),
                       {r.si(F::JointState::yaw), r.si(F::JointState::pitch), r.si(F::JointState::insertion)}};
      break;
    case MessageKind::CurrentCommand:
      out = CurrentCommand{node, r.u8(F::CurrentCommand::counter), static_cast<CommandMode>(r.u8(F::CurrentCommand::mode)),
                           {r.si(F::CurrentCommand::yaw), r.si(F::CurrentCommand::pitch), r.si(F::CurrentCommand::insertion)}};
      break;
    case MessageKind::AuxState:
      out = AuxState{node, r.u8(F::AuxState::counter), r.flag(F::AuxState::pedal), r.flag(F::AuxState::estop_input),
                     r.flag(F::AuxState::handle_button), r.si(F::AuxState::roll), r.si(F::AuxState::jaw),
                     r.si(F::AuxState::bus_voltage)};
      if ((d[1] & 0xF8) != 0) return DecodeError::OutOfRange;  // reserved input bits must be zero
      break;
    case MessageKind::Control:
      out = Control{node, r.u8(F::Control::counter), static_cast<ControlCommand>(r.u8(F::Control::command))};
      break;
    case MessageKind::CurrentState:
      out = CurrentState{node, r.u8(F::CurrentState::counter), static_cast<std::int8_t>(r.raw(F::CurrentState::board_temperature)),
                         {r.si(F::CurrentState::yaw), r.si(F::CurrentState::pitch), r.si(F::CurrentState::insertion)}};
      break;
    case MessageKind::CalibrationCommand:
      out = CalibrationCommand{node, static_cast<CalibrationProcedure>(r.u8(F::CalibrationCommand::procedure)),
                               r.u8(F::CalibrationCommand::joint_mask), r.si(F::CalibrationCommand::max_current)};
      break;
    case MessageKind::CalibrationProgress:
      out = CalibrationProgress{node, static_cast<CalibrationProcedure>(r.u8(F::CalibrationProgress::procedure)),
                                static_cast<CalibrationStatus>(r.u8(F::CalibrationProgress::status)),
                                r.u8(F::CalibrationProgress::percent), r.u8(F::CalibrationProgress::joint),
                                static_cast<std::int32_t>(r.raw(F::CalibrationProgress::result))};
      break;
    case MessageKind::Identity: {
      Identity id{node, r.u8(F::Identity::protocol_major), r.u8(F::Identity::min_minor), r.u8(F::Identity::max_minor),
                  r.u8(F::Identity::negotiated_minor), static_cast<std::uint32_t>(r.raw(F::Identity::serial))};
      if (r.error == DecodeError::None && id.min_minor > id.max_minor) return DecodeError::Inconsistent;
      out = id;
      break;
    }
    case MessageKind::Hello:
      out = Hello{node, r.u8(F::Hello::protocol_major), r.u8(F::Hello::protocol_minor)};
      break;
    case MessageKind::ParameterRequest:
      out = ParameterRequest{node, static_cast<ParameterOp>(r.u8(F::ParameterRequest::op)),
                             static_cast<ParameterType>(r.u8(F::ParameterRequest::type)),
                             static_cast<std::uint16_t>(r.raw(F::ParameterRequest::index)),
                             static_cast<std::uint32_t>(r.raw(F::ParameterRequest::value))};
      break;
    case MessageKind::ParameterResponse:
      out = ParameterResponse{node, static_cast<ParameterOp>(r.u8(F::ParameterResponse::op)),
                              r.flag(F::ParameterResponse::aborted),
                              static_cast<ParameterType>(r.u8(F::ParameterResponse::type)),
                              static_cast<std::uint16_t>(r.raw(F::ParameterResponse::index)),
                              static_cast<std::uint32_t>(r.raw(F::ParameterResponse::value))};
      break;
    case MessageKind::Heartbeat: {
      Heartbeat h{node, static_cast<NodeState>(r.u8(F::Heartbeat::state)), r.flag(F::Heartbeat::enabled),
                  static_cast<FaultCode>(r.u8(F::Heartbeat::latched_fault)), r.flag(F::Heartbeat::not_homed)};
      const std::int64_t code = r.raw(F::Heartbeat::canopen_state);
      if ((d[1] & 0xE0) != 0) return DecodeError::OutOfRange;  // reserved bits
      if (r.error == DecodeError::None && code != canopen_heartbeat_code(h.state)) return DecodeError::Inconsistent;
      out = h;
      break;
    }
  }
  return r.error;
}

}  // namespace

bool classify_id(std::uint32_t id, MessageKind& kind, std::uint8_t& node) {
  if (id > 0x7FF) return false;
  for (const MessageSpec& s : kMessageSpecs) {
    if (!s.per_node) {
      if (id == s.base_id) { kind = s.kind; node = 0; return true; }
    } else if (id > s.base_id && id <= static_cast<std::uint32_t>(s.base_id + kMaxNodeId)) {
      kind = s.kind;
      node = static_cast<std::uint8_t>(id - s.base_id);
      return true;
    }
  }
  return false;
}

MessageKind kind_of(const Message& m) { return static_cast<MessageKind>(m.index()); }

std::uint8_t node_of(const Message& m) {
  switch (kind_of(m)) {
    case MessageKind::Nmt: case MessageKind::EStop: case MessageKind::Sync: return 0;
    default: break;
  }
  // Every per-node message struct starts with `node`.
  if (auto* p = std::get_if<Emergency>(&m)) return p->node;
  if (auto* p = std::get_if<JointState>(&m)) return p->node;
  if (auto* p = std::get_if<CurrentCommand>(&m)) return p->node;
  if (auto* p = std::get_if<AuxState>(&m)) return p->node;
  if (auto* p = std::get_if<Control>(&m)) return p->node;
  if (auto* p = std::get_if<CurrentState>(&m)) return p->node;
  if (auto* p = std::get_if<CalibrationCommand>(&m)) return p->node;
  if (auto* p = std::get_if<CalibrationProgress>(&m)) return p->node;
  if (auto* p = std::get_if<Identity>(&m)) return p->node;
  if (auto* p = std::get_if<Hello>(&m)) return p->node;
  if (auto* p = std::get_if<ParameterRequest>(&m)) return p->node;
  if (auto* p = std::get_if<ParameterResponse>(&m)) return p->node;
  if (auto* p = std::get_if<Heartbeat>(&m)) return p->node;
  return 0;
}

EncodeError encode(const Message& message, CanFrame& out) {
  const MessageSpec& s = spec_of(kind_of(message));
  const std::uint8_t node = node_of(message);
  if (s.per_node && (node == 0 || node > kMaxNodeId)) return EncodeError::BadNode;
  CanFrame f;
  f.id = can_id(s.kind, node);
  f.len = s.length;
  const EncodeError e = encode_payload(message, f.data);
  if (e != EncodeError::None) return e;
  out = f;
  return EncodeError::None;
}

DecodeError decode(const CanFrame& frame, Message& out) {
  if (frame.extended()) return DecodeError::UnknownId;
  if (frame.remote()) return DecodeError::RemoteFrame;
  MessageKind kind;
  std::uint8_t node;
  if (!classify_id(frame.id, kind, node)) return DecodeError::UnknownId;
  if (frame.len != spec_of(kind).length) return DecodeError::WrongLength;
  Message m;
  const DecodeError e = decode_payload(kind, node, frame.data, m);
  if (e != DecodeError::None) return e;
  out = m;
  return DecodeError::None;
}

const char* to_string(DecodeError e) {
  switch (e) {
    case DecodeError::None: return "none";
    case DecodeError::UnknownId: return "unknown_id";
    case DecodeError::RemoteFrame: return "remote_frame";
    case DecodeError::WrongLength: return "wrong_length";
    case DecodeError::OutOfRange: return "out_of_range";
    case DecodeError::Inconsistent: return "inconsistent";
    case DecodeError::BadCounter: return "bad_counter";
  }
  return "?";
}

const char* to_string(EncodeError e) {
  switch (e) {
    case EncodeError::None: return "none";
    case EncodeError::BadNode: return "bad_node";
    case EncodeError::OutOfRange: return "out_of_range";
  }
  return "?";
}

const char* to_string(NodeState s) {
  switch (s) {
    case NodeState::Boot: return "boot";
    case NodeState::PreOperational: return "pre-operational";
    case NodeState::Operational: return "operational";
    case NodeState::Stopped: return "stopped";
    case NodeState::Fault: return "fault";
  }
  return "?";
}

const char* to_string(Limiter l) {
  switch (l) {
    case Limiter::None: return "none";
    case Limiter::Current: return "current";
    case Limiter::Torque: return "torque";
    case Limiter::Velocity: return "velocity";
    case Limiter::JointRange: return "joint_range";
    case Limiter::Disabled: return "disabled";
    case Limiter::Fault: return "fault";
  }
  return "?";
}

const char* to_string(FaultCode f) {
  switch (f) {
    case FaultCode::None: return "none";
    case FaultCode::CommandWatchdog: return "command_watchdog";
    case FaultCode::EmergencyStop: return "emergency_stop";
    case FaultCode::OverCurrent: return "over_current";
    case FaultCode::OverSpeed: return "over_speed";
    case FaultCode::JointRangeExceeded: return "joint_range_exceeded";
    case FaultCode::ParameterCrc: return "parameter_crc";
    case FaultCode::UnderVoltage: return "under_voltage";
    case FaultCode::OverVoltage: return "over_voltage";
    case FaultCode::OverTemperature: return "over_temperature";
    case FaultCode::ProtocolMismatch: return "protocol_mismatch";
  }
  return "?";
}

}  // namespace vesica::fp
