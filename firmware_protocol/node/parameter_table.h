// The node's typed parameters: index, name, type, unit, range, default, access. One table shared by
// the node (parameter_store.h), the host tools and docs/protocol.md's parameter table.
// Use: find_parameter(index) -> const ParameterSpec* (nullptr: NoSuchParameter abort).
// Freestanding C++17.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware_protocol/codec/protocol_enums.h"

namespace vesica::fp {

enum class ParameterAccess : std::uint8_t { ReadWrite, ReadOnly };

struct ParameterSpec {
  std::uint16_t index;
  const char* name;  // unit in the name where not SI
  ParameterType type;
  const char* unit;
  double min;
  double max;
  double default_value;
  ParameterAccess access;
  bool persistent;  // saved in the CRC-protected block
};

// Parameter indices (names say the unit). Per-joint parameters: base + joint (0 yaw, 1 pitch, 2 insertion).
namespace param {
inline constexpr std::uint16_t kNodeId = 0x0001;
inline constexpr std::uint16_t kWatchdogTimeout_us = 0x0002;
inline constexpr std::uint16_t kHeartbeatPeriod_ms = 0x0003;
inline constexpr std::uint16_t kAuxPeriod_ms = 0x0004;
inline constexpr std::uint16_t kOverspeedFactor = 0x0005;
inline constexpr std::uint16_t kOvercurrentFactor = 0x0006;
inline constexpr std::uint16_t kMinBus_V = 0x0007;
inline constexpr std::uint16_t kMaxBus_V = 0x0008;
inline constexpr std::uint16_t kMaxBoardTemperature_degC = 0x0009;
inline constexpr std::uint16_t kMaxCurrent = 0x0010;        // A
inline constexpr std::uint16_t kTorqueConstant = 0x0020;    // N·m/A at the motor
inline constexpr std::uint16_t kGearRatio = 0x0030;         // joint torque = motor torque * ratio
inline constexpr std::uint16_t kMaxTorque = 0x0040;         // N·m (N for insertion) at the joint
inline constexpr std::uint16_t kMaxVelocity = 0x0050;       // rad/s (m/s)
inline constexpr std::uint16_t kJointMin = 0x0060;          // rad (m)
inline constexpr std::uint16_t kJointMax = 0x0070;          // rad (m)
inline constexpr std::uint16_t kPositionOffset = 0x0080;    // rad (m), from calibration
inline constexpr std::uint16_t kCurrentOffset = 0x0090;     // A, from calibration
// Protocol minor 1: what the calibration tool measures (docs/protocol.md section 11).
inline constexpr std::uint16_t kEncoderDirection = 0x00A0;  // +1 / -1: sign of counts per joint motion
inline constexpr std::uint16_t kIndexPosition = 0x00A8;     // rad (m): joint position of the reference index edge
inline constexpr std::uint16_t kCoulombFriction = 0x00B0;   // N·m (N) at the joint, in the node's torque units
inline constexpr std::uint16_t kViscousFriction = 0x00B8;   // N·m·s/rad (N·s/m)
inline constexpr std::uint16_t kGravitySin = 0x00C0;        // N·m: pitch holding torque = sin * sin(pitch) + cos * cos(pitch)
inline constexpr std::uint16_t kGravityCos = 0x00C1;        // N·m
inline constexpr std::uint16_t kSerial = 0x0100;
inline constexpr std::uint16_t kFirmwareVersion = 0x0101;
inline constexpr std::uint16_t kFaultHistoryCount = 0x0102;
inline constexpr std::uint16_t kDecodeErrorCount = 0x0103;
inline constexpr std::uint16_t kLostCommandCount = 0x0104;
inline constexpr std::uint16_t kFaultHistory = 0x0110;      // 0x0110..0x0117, newest first
inline constexpr std::uint8_t kFaultHistoryDepth = 8;
// Calibration slots (protocol minor 1). Date and tool version are written by the tool before a
// save and go into the slot header; after boot they are the booted slot's.
inline constexpr std::uint16_t kCalibrationDate_s = 0x0120;      // Unix time
inline constexpr std::uint16_t kCalibrationToolVersion = 0x0121; // major << 16 | minor << 8 | patch
inline constexpr std::uint16_t kActiveSlot = 0x0122;             // 0 A, 1 B, 255 none (defaults)
inline constexpr std::uint16_t kSlotStatus = 0x0123;             // 0x0123 A, 0x0124 B: StorageResult
inline constexpr std::uint16_t kSlotGeneration = 0x0125;         // 0x0125 A, 0x0126 B
// Protocol minor 3, image layout 2: what the torque-constant check and the guided hand steps
// measure, stored so that the node and the bridge use it (docs/protocol.md section 9).
inline constexpr std::uint16_t kTorqueConstantCorrection = 0x00D0;  // real torque per node torque unit, per joint
inline constexpr std::uint16_t kRollSensorOffset = 0x00D8;   // rad: what the roll sensor reads at the roll mark
inline constexpr std::uint16_t kJawClosedCounts = 0x00D9;    // jaw ADC, handle fully closed
inline constexpr std::uint16_t kJawOpenCounts = 0x00DA;      // jaw ADC, handle fully open (= closed: not measured)
inline constexpr std::uint16_t kJawOpen_rad = 0x00DB;        // the handle's full opening (design)
inline constexpr std::uint16_t kPedalReleasedCounts = 0x00DC;  // pedal ADC, released
inline constexpr std::uint16_t kPedalPressedCounts = 0x00DD;   // pedal ADC at its stop (= released: not measured)
inline constexpr std::uint16_t kStoredLayout = 0x0127;  // image layout of the booted slot: 0 none, 1, 2
}  // namespace param

#define VESICA_J3(base, name, unit, lo, hi, def0, def1, def2)                                  \
  {base + 0, name "[yaw]", ParameterType::F32, unit, lo, hi, def0, ParameterAccess::ReadWrite, true}, \
  {base + 1, name "[pitch]", ParameterType::F32, unit, lo, hi, def1, ParameterAccess::ReadWrite, true}, \
  {base + 2, name "[insertion]", ParameterType::F32, unit, lo, hi, def2, ParameterAccess::ReadWrite, true}

inline constexpr ParameterSpec kParameterSpecs[] = {
  {param::kNodeId, "node_id", ParameterType::U32, "", 1, 127, 1, ParameterAccess::ReadWrite, true},
  {param::kWatchdogTimeout_us, "watchdog_timeout_us", ParameterType::U32, "us", 500, 100000, 3000, ParameterAccess::ReadWrite, true},
  {param::kHeartbeatPeriod_ms, "heartbeat_period_ms", ParameterType::U32, "ms", 10, 10000, 100, ParameterAccess::ReadWrite, true},
  {param::kAuxPeriod_ms, "aux_period_ms", ParameterType::U32, "ms", 1, 1000, 10, ParameterAccess::ReadWrite, true},
  {param::kOverspeedFactor, "overspeed_factor", ParameterType::F32, "", 1, 10, 2, ParameterAccess::ReadWrite, true},
  {param::kOvercurrentFactor, "overcurrent_factor", ParameterType::F32, "", 1, 5, 1.5, ParameterAccess::ReadWrite, true},
  {param::kMinBus_V, "min_bus_V", ParameterType::F32, "V", 0, 100, 10, ParameterAccess::ReadWrite, true},
  {param::kMaxBus_V, "max_bus_V", ParameterType::F32, "V", 0, 100, 48, ParameterAccess::ReadWrite, true},
  {param::kMaxBoardTemperature_degC, "max_board_temperature_degC", ParameterType::F32, "degC", 0, 125, 80, ParameterAccess::ReadWrite, true},
  VESICA_J3(param::kMaxCurrent, "max_current", "A", 0, 30, 3.0, 3.0, 5.0),
  VESICA_J3(param::kTorqueConstant, "torque_constant", "N·m/A", 1e-4, 10, 0.0302, 0.0302, 0.0276),
  VESICA_J3(param::kGearRatio, "gear_ratio", "", 1e-3, 1000, 14.0, 14.0, 100.0),
  VESICA_J3(param::kMaxTorque, "max_torque", "N·m (N)", 0, 1000, 1.2, 1.2, 10.0),
  VESICA_J3(param::kMaxVelocity, "max_velocity", "rad/s (m/s)", 0, 100, 6.0, 6.0, 1.0),
  VESICA_J3(param::kJointMin, "joint_min", "rad (m)", -3.1416, 3.1416, -1.0, -1.0, 0.0),
  VESICA_J3(param::kJointMax, "joint_max", "rad (m)", -3.1416, 3.1416, 1.0, 1.0, 0.25),
  VESICA_J3(param::kPositionOffset, "position_offset", "rad (m)", -10, 10, 0, 0, 0),
  VESICA_J3(param::kCurrentOffset, "current_offset", "A", -5, 5, 0, 0, 0),
  {param::kEncoderDirection + 0, "encoder_direction[yaw]", ParameterType::I32, "", -1, 1, 1, ParameterAccess::ReadWrite, true},
  {param::kEncoderDirection + 1, "encoder_direction[pitch]", ParameterType::I32, "", -1, 1, 1, ParameterAccess::ReadWrite, true},
  {param::kEncoderDirection + 2, "encoder_direction[insertion]", ParameterType::I32, "", -1, 1, 1, ParameterAccess::ReadWrite, true},
  VESICA_J3(param::kIndexPosition, "index_position", "rad (m)", -10, 10, 0, 0, 0),
  VESICA_J3(param::kCoulombFriction, "coulomb_friction", "N·m (N)", 0, 100, 0, 0, 0),
  VESICA_J3(param::kViscousFriction, "viscous_friction", "N·m·s/rad (N·s/m)", 0, 1000, 0, 0, 0),
  {param::kGravitySin, "gravity_sin[pitch]", ParameterType::F32, "N·m", -100, 100, 0, ParameterAccess::ReadWrite, true},
  {param::kGravityCos, "gravity_cos[pitch]", ParameterType::F32, "N·m", -100, 100, 0, ParameterAccess::ReadWrite, true},
  {param::kSerial, "serial", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, false},
  {param::kFirmwareVersion, "firmware_version", ParameterType::U32, "", 0, 4294967295.0, 0x00010000, ParameterAccess::ReadOnly, false},
  {param::kFaultHistoryCount, "fault_history_count", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kDecodeErrorCount, "decode_error_count", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, false},
  {param::kLostCommandCount, "lost_command_count", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, false},
  {param::kFaultHistory + 0, "fault_history[0]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kFaultHistory + 1, "fault_history[1]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kFaultHistory + 2, "fault_history[2]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kFaultHistory + 3, "fault_history[3]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kFaultHistory + 4, "fault_history[4]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kFaultHistory + 5, "fault_history[5]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kFaultHistory + 6, "fault_history[6]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kFaultHistory + 7, "fault_history[7]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, true},
  {param::kCalibrationDate_s, "calibration_date_s", ParameterType::U32, "s", 0, 4294967295.0, 0, ParameterAccess::ReadWrite, false},
  {param::kCalibrationToolVersion, "calibration_tool_version", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadWrite, false},
  {param::kActiveSlot, "active_slot", ParameterType::U32, "", 0, 255, 255, ParameterAccess::ReadOnly, false},
  {param::kSlotStatus + 0, "slot_status[A]", ParameterType::U32, "", 0, 4, 1, ParameterAccess::ReadOnly, false},
  {param::kSlotStatus + 1, "slot_status[B]", ParameterType::U32, "", 0, 4, 1, ParameterAccess::ReadOnly, false},
  {param::kSlotGeneration + 0, "slot_generation[A]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, false},
  {param::kSlotGeneration + 1, "slot_generation[B]", ParameterType::U32, "", 0, 4294967295.0, 0, ParameterAccess::ReadOnly, false},
  // ---- image layout 2 (protocol minor 3) from here on: appended, so that a layout-1 image is
  // the first kLayout1ParameterCount entries and migrates by position. Defaults are neutral: a
  // torque constant as the parameter says, the roll sensor as it reads, jaw and pedal as the board
  // converts them (closed = open, released = pressed: not measured).
  VESICA_J3(param::kTorqueConstantCorrection, "torque_constant_correction", "", 0.5, 2.0, 1.0, 1.0, 1.0),
  {param::kRollSensorOffset, "roll_sensor_offset", ParameterType::F32, "rad", -3.1416, 3.1416, 0, ParameterAccess::ReadWrite, true},
  {param::kJawClosedCounts, "jaw_closed_counts", ParameterType::U32, "", 0, 4095, 0, ParameterAccess::ReadWrite, true},
  {param::kJawOpenCounts, "jaw_open_counts", ParameterType::U32, "", 0, 4095, 0, ParameterAccess::ReadWrite, true},
  {param::kJawOpen_rad, "jaw_open_rad", ParameterType::F32, "rad", 0.05, 3.1416, 0.6, ParameterAccess::ReadWrite, true},
  {param::kPedalReleasedCounts, "pedal_released_counts", ParameterType::U32, "", 0, 4095, 0, ParameterAccess::ReadWrite, true},
  {param::kPedalPressedCounts, "pedal_pressed_counts", ParameterType::U32, "", 0, 4095, 0, ParameterAccess::ReadWrite, true},
  {param::kStoredLayout, "stored_layout", ParameterType::U32, "", 0, 2, 0, ParameterAccess::ReadOnly, false},
};
#undef VESICA_J3

inline constexpr std::size_t kParameterCount = sizeof(kParameterSpecs) / sizeof(kParameterSpecs[0]);

// Image layout 1 (protocol 1.0 .. 1.2) held the table's first 70 parameters, in this order.
inline constexpr std::size_t kLayout1ParameterCount = 70;
static_assert(kParameterSpecs[kLayout1ParameterCount - 1].index == param::kSlotGeneration + 1,
              "layout 1 ends with slot_generation[B]: new parameters are appended after it, never inserted");
// The protocol minor that brought layout 2's parameters: a node below it has none of them.
inline constexpr std::uint8_t kLayout2Minor = 3;
// The image layout that first held kParameterSpecs[i].
constexpr std::uint16_t parameter_layout(std::size_t i) { return i < kLayout1ParameterCount ? 1 : 2; }

// Position of a parameter in kParameterSpecs, or -1.
constexpr int parameter_slot(std::uint16_t index) {
  for (std::size_t i = 0; i < kParameterCount; ++i)
    if (kParameterSpecs[i].index == index) return static_cast<int>(i);
  return -1;
}

constexpr const ParameterSpec* find_parameter(std::uint16_t index) {
  const int slot = parameter_slot(index);
  return slot < 0 ? nullptr : &kParameterSpecs[slot];
}

}  // namespace vesica::fp
