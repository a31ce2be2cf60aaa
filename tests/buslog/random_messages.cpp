// Random messages built as structs and encoded by the codec, so the cross-field rules (EMCY code
// from the fault, heartbeat byte from the state) hold; kinds added later fall back to random raw
// field values kept only when the codec accepts them.
#include "random_messages.h"

#include <stdexcept>

#include "firmware_protocol/wireshark/field_bits.h"

namespace vesica::fp::test {
namespace {

namespace F = fields;

std::uint8_t u8(std::mt19937& rng, int lo, int hi) { return static_cast<std::uint8_t>(lo + static_cast<int>(rng() % (hi - lo + 1))); }
float si(std::mt19937& rng, const FieldSpec& f) {
  const std::int64_t lo = raw_min(f), hi = raw_max(f);
  return static_cast<float>(static_cast<double>(lo + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(hi - lo + 1))) * f.lsb);
}

bool random_message(MessageKind kind, std::mt19937& rng, Message& out) {
  const std::uint8_t node = u8(rng, 1, kMaxNodeId);
  const std::uint8_t counter = u8(rng, 0, 255);
  switch (kind) {
    case MessageKind::Nmt: {
      constexpr NmtCommand kCommands[] = {NmtCommand::Start, NmtCommand::Stop, NmtCommand::EnterPreOperational,
                                          NmtCommand::ResetNode, NmtCommand::ResetCommunication};
      out = Nmt{kCommands[rng() % 5], u8(rng, 0, 127)};
      return true;
    }
    case MessageKind::EStop: out = EStop{u8(rng, 0, 127)}; return true;
    case MessageKind::Sync: out = Sync{counter}; return true;
    case MessageKind::Emergency:
      out = Emergency{node, static_cast<FaultCode>(u8(rng, 0, kFaultCodeCount - 1)), u8(rng, 0, 255), u8(rng, 0, 255),
                      static_cast<std::int16_t>(rng())};
      return true;
    case MessageKind::JointState:
      out = JointState{node, counter, static_cast<NodeState>(u8(rng, 0, kNodeStateCount - 1)), rng() % 2 == 0,
                       static_cast<Limiter>(u8(rng, 0, kLimiterCount - 1)),
                       {si(rng, F::JointState::yaw), si(rng, F::JointState::pitch), si(rng, F::JointState::insertion)}};
      return true;
    case MessageKind::CurrentCommand:
      out = CurrentCommand{node, counter, static_cast<CommandMode>(u8(rng, 0, 1)),
                           {si(rng, F::CurrentCommand::yaw), si(rng, F::CurrentCommand::pitch), si(rng, F::CurrentCommand::insertion)}};
      return true;
    case MessageKind::AuxState:
      out = AuxState{node, counter, rng() % 2 == 0, rng() % 2 == 0, rng() % 2 == 0, si(rng, F::AuxState::roll),
                     si(rng, F::AuxState::jaw), si(rng, F::AuxState::bus_voltage)};
      return true;
    case MessageKind::Control: out = Control{node, counter, static_cast<ControlCommand>(u8(rng, 1, 3))}; return true;
    case MessageKind::CurrentState:
      out = CurrentState{node, counter, static_cast<std::int8_t>(u8(rng, 0, 165) - 40),
                         {si(rng, F::CurrentState::yaw), si(rng, F::CurrentState::pitch), si(rng, F::CurrentState::insertion)}};
      return true;
    case MessageKind::Heartbeat:
      out = Heartbeat{node, static_cast<NodeState>(u8(rng, 0, kNodeStateCount - 1)), rng() % 2 == 0,
                      static_cast<FaultCode>(u8(rng, 0, kFaultCodeCount - 1))};
      return true;
    default: return false;  // the rest: random raw values (below)
  }
}

}  // namespace

CanFrame random_valid_frame(MessageKind kind, std::mt19937& rng) {
  CanFrame f;
  Message m;
  if (random_message(kind, rng, m)) {
    if (encode(m, f) != EncodeError::None) throw std::logic_error(std::string("cannot encode a random ") + spec_of(kind).name);
    return f;
  }
  const MessageSpec& s = spec_of(kind);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    f = CanFrame{};
    f.id = can_id(kind, u8(rng, 1, kMaxNodeId));
    f.len = s.length;
    for (const FieldSpec* field : kAllFields) {
      if (field->message != kind) continue;
      const std::int64_t lo = raw_min(*field), hi = raw_max(*field);
      write_field_raw(f, *field, lo + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(hi - lo + 1)));
    }
    if (decode(f, m) == DecodeError::None) return f;
  }
  throw std::logic_error(std::string("no valid random ") + s.name + " in 100,000 tries");
}

std::map<std::string, double> codec_field_values(const Message& m) {
  std::map<std::string, double> v;
  auto put = [&](const FieldSpec& f, double x) { v[f.name] = x; };
  if (auto* p = std::get_if<Nmt>(&m)) {
    put(F::Nmt::command, static_cast<double>(p->command));
    put(F::Nmt::target_node, p->target_node);
    return v;
  }
  if (auto* p = std::get_if<EStop>(&m)) {
    put(F::EStop::magic, 0xE5);
    put(F::EStop::source_node, p->source_node);
    return v;
  }
  if (auto* p = std::get_if<Sync>(&m)) {
    put(F::Sync::counter, p->counter);
    return v;
  }
  if (auto* p = std::get_if<Emergency>(&m)) {
    put(F::Emergency::error_code, emcy_error_code(p->fault));
    put(F::Emergency::error_register, emcy_error_register(p->fault));
    put(F::Emergency::fault, static_cast<double>(p->fault));
    put(F::Emergency::joint, p->joint);
    put(F::Emergency::history_count, p->history_count);
    put(F::Emergency::detail, p->detail);
    return v;
  }
  if (auto* p = std::get_if<JointState>(&m)) {
    put(F::JointState::counter, p->counter);
    put(F::JointState::state, static_cast<double>(p->state));
    put(F::JointState::enabled, p->enabled);
    put(F::JointState::limiter, static_cast<double>(p->limiter));
    put(F::JointState::yaw, p->position[0]);
    put(F::JointState::pitch, p->position[1]);
    put(F::JointState::insertion, p->position[2]);
    return v;
  }
  if (auto* p = std::get_if<CurrentCommand>(&m)) {
    put(F::CurrentCommand::counter, p->counter);
    put(F::CurrentCommand::mode, static_cast<double>(p->mode));
    put(F::CurrentCommand::yaw, p->value[0]);
    put(F::CurrentCommand::pitch, p->value[1]);
    put(F::CurrentCommand::insertion, p->value[2]);
    return v;
  }
  if (auto* p = std::get_if<AuxState>(&m)) {
    put(F::AuxState::counter, p->counter);
    put(F::AuxState::pedal, p->pedal);
    put(F::AuxState::estop_input, p->estop_input);
    put(F::AuxState::handle_button, p->handle_button);
    put(F::AuxState::roll, p->roll_rad);
    put(F::AuxState::jaw, p->jaw_rad);
    put(F::AuxState::bus_voltage, p->bus_V);
    return v;
  }
  if (auto* p = std::get_if<Control>(&m)) {
    put(F::Control::command, static_cast<double>(p->command));
    put(F::Control::counter, p->counter);
    return v;
  }
  if (auto* p = std::get_if<CurrentState>(&m)) {
    put(F::CurrentState::counter, p->counter);
    put(F::CurrentState::board_temperature, p->board_temperature_degC);
    put(F::CurrentState::yaw, p->current[0]);
    put(F::CurrentState::pitch, p->current[1]);
    put(F::CurrentState::insertion, p->current[2]);
    return v;
  }
  if (auto* p = std::get_if<CalibrationCommand>(&m)) {
    put(F::CalibrationCommand::procedure, static_cast<double>(p->procedure));
    put(F::CalibrationCommand::joint_mask, p->joint_mask);
    put(F::CalibrationCommand::max_current, p->max_current);
    return v;
  }
  if (auto* p = std::get_if<CalibrationProgress>(&m)) {
    put(F::CalibrationProgress::procedure, static_cast<double>(p->procedure));
    put(F::CalibrationProgress::status, static_cast<double>(p->status));
    put(F::CalibrationProgress::percent, p->percent);
    put(F::CalibrationProgress::joint, p->joint);
    put(F::CalibrationProgress::result, p->result);
    return v;
  }
  if (auto* p = std::get_if<Identity>(&m)) {
    put(F::Identity::protocol_major, p->protocol_major);
    put(F::Identity::min_minor, p->min_minor);
    put(F::Identity::max_minor, p->max_minor);
    put(F::Identity::negotiated_minor, p->negotiated_minor);
    put(F::Identity::serial, p->serial);
    return v;
  }
  if (auto* p = std::get_if<Hello>(&m)) {
    put(F::Hello::protocol_major, p->protocol_major);
    put(F::Hello::protocol_minor, p->protocol_minor);
    return v;
  }
  if (auto* p = std::get_if<ParameterRequest>(&m)) {
    put(F::ParameterRequest::op, static_cast<double>(p->op));
    put(F::ParameterRequest::type, static_cast<double>(p->type));
    put(F::ParameterRequest::index, p->index);
    put(F::ParameterRequest::value, p->raw_value);
    return v;
  }
  if (auto* p = std::get_if<ParameterResponse>(&m)) {
    put(F::ParameterResponse::op, static_cast<double>(p->op));
    put(F::ParameterResponse::aborted, p->aborted);
    put(F::ParameterResponse::type, static_cast<double>(p->type));
    put(F::ParameterResponse::index, p->index);
    put(F::ParameterResponse::value, p->raw_value);
    return v;
  }
  if (auto* p = std::get_if<Heartbeat>(&m)) {
    put(F::Heartbeat::canopen_state, canopen_heartbeat_code(p->state));
    put(F::Heartbeat::state, static_cast<double>(p->state));
    put(F::Heartbeat::enabled, p->enabled);
    put(F::Heartbeat::latched_fault, static_cast<double>(p->latched_fault));
  }
  return v;
}

}  // namespace vesica::fp::test
