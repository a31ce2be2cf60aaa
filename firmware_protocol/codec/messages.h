// Decoded Vesica CAN messages, in SI units (names say when not: _mA, _degC, _us).
// Use: build a Message from one of these structs, encode() it (codec.h); decode() gives them back.
// Byte layouts, scaling and ranges live once in message_table.h and docs/protocol.md.
// Freestanding C++17: plain structs, std::variant without heap.
#pragma once

#include <array>
#include <cstdint>
#include <variant>

#include "firmware_protocol/codec/protocol_enums.h"

namespace vesica::fp {

using JointArray = std::array<float, kJointCount>;  // yaw, pitch, insertion

// NMT (id 0x000), host -> nodes. node 0 addresses all nodes.
struct Nmt { NmtCommand command = NmtCommand::Start; std::uint8_t target_node = 0; };
// Emergency stop broadcast (id 0x001), any -> all: zero torque and latch FaultCode::EmergencyStop.
struct EStop { std::uint8_t source_node = 0; };
// SYNC (id 0x080), host -> nodes: every operational node answers with JointState.
struct Sync { std::uint8_t counter = 0; };

// EMCY (0x080 + node), node -> host, on every fault and on fault reset (code None).
struct Emergency {
  std::uint8_t node = 0;
  FaultCode fault = FaultCode::None;
  std::uint8_t joint = 0xFF;          // 0..2, 0xFF when not joint-specific
  std::uint8_t history_count = 0;     // faults recorded since storage was cleared (saturates at 255)
  std::int16_t detail = 0;            // fault-specific raw value (docs/protocol.md EMCY table)
};

// Joint state (0x180 + node), node -> host, answering each CurrentCommand or SYNC (1 kHz).
struct JointState {
  std::uint8_t node = 0;
  std::uint8_t counter = 0;
  NodeState state = NodeState::Boot;
  bool enabled = false;
  Limiter limiter = Limiter::None;
  JointArray position{};  // rad, rad, m  (yaw, pitch about the remote centre; insertion)
};

// Current / torque command (0x200 + node), host -> node, 1 kHz; feeds the command watchdog.
struct CurrentCommand {
  std::uint8_t node = 0;
  std::uint8_t counter = 0;
  CommandMode mode = CommandMode::MotorCurrent;
  JointArray value{};  // A (MotorCurrent) or N·m at the joint (JointTorque)
};

// Auxiliary inputs (0x280 + node), node -> host, 100 Hz.
struct AuxState {
  std::uint8_t node = 0;
  std::uint8_t counter = 0;
  bool pedal = false;
  bool estop_input = false;
  bool handle_button = false;
  float roll_rad = 0;
  float jaw_rad = 0;
  float bus_V = 0;
};

// Control (0x300 + node), host -> node: explicit enable, disable, fault reset.
struct Control {
  std::uint8_t node = 0;
  std::uint8_t counter = 0;
  ControlCommand command = ControlCommand::Disable;
};

// Measured motor currents (0x380 + node), node -> host, 100 Hz.
struct CurrentState {
  std::uint8_t node = 0;
  std::uint8_t counter = 0;
  std::int8_t board_temperature_degC = 0;
  JointArray current{};  // A
};

struct CalibrationCommand {  // 0x400 + node, host -> node
  std::uint8_t node = 0;
  CalibrationProcedure procedure = CalibrationProcedure::Abort;
  std::uint8_t joint_mask = 0;  // bit j = joint j
  float max_current = 0;        // A, bound on the current the procedure may apply
};

struct CalibrationProgress {  // 0x480 + node, node -> host, 10 Hz while running and once at the end
  std::uint8_t node = 0;
  CalibrationProcedure procedure = CalibrationProcedure::Abort;
  CalibrationStatus status = CalibrationStatus::Idle;
  std::uint8_t percent = 0;  // 0..100
  std::uint8_t joint = 0;
  std::int32_t result = 0;   // procedure-specific raw result (docs/protocol.md)
};

// Identity and protocol versions (0x500 + node), node -> host: at boot and in answer to Hello.
struct Identity {
  std::uint8_t node = 0;
  std::uint8_t protocol_major = kProtocolMajor;
  std::uint8_t min_minor = 0;
  std::uint8_t max_minor = kProtocolMinor;
  std::uint8_t negotiated_minor = 0xFF;  // 0xFF: nothing negotiated (node refuses Enable)
  std::uint32_t serial = 0;
};

// Hello (0x680 + node), host -> node: the protocol version the host speaks.
struct Hello {
  std::uint8_t node = 0;
  std::uint8_t protocol_major = kProtocolMajor;
  std::uint8_t protocol_minor = kProtocolMinor;
};

// Typed parameter channel, expedited only (CANopen SDO-like, one request outstanding per node).
struct ParameterRequest {  // 0x600 + node, host -> node
  std::uint8_t node = 0;
  ParameterOp op = ParameterOp::Read;
  ParameterType type = ParameterType::None;
  std::uint16_t index = 0;
  std::uint32_t raw_value = 0;  // bit pattern of a u32 / i32 / f32
};
struct ParameterResponse {  // 0x580 + node, node -> host
  std::uint8_t node = 0;
  ParameterOp op = ParameterOp::Read;
  bool aborted = false;
  ParameterType type = ParameterType::None;
  std::uint16_t index = 0;
  std::uint32_t raw_value = 0;  // value, or the AbortCode when aborted
};

// Heartbeat (0x700 + node), node -> host, 10 Hz; byte 0 is the CANopen heartbeat state.
struct Heartbeat {
  std::uint8_t node = 0;
  NodeState state = NodeState::Boot;
  bool enabled = false;
  FaultCode latched_fault = FaultCode::None;
  bool not_homed = false;  // protocol 1.4: positions unknown since power-up, Enable refused until homed
};

using Message = std::variant<Nmt, EStop, Sync, Emergency, JointState, CurrentCommand, AuxState, Control,
                             CurrentState, CalibrationCommand, CalibrationProgress, Identity, Hello,
                             ParameterRequest, ParameterResponse, Heartbeat>;

}  // namespace vesica::fp
