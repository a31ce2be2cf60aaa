// The small enumerations carried inside Vesica CAN messages (docs/protocol.md lists every value).
// Use: as fields of the message structs in messages.h; to_string() names a value for logs and tests.
// Freestanding C++17.
#pragma once

#include <cstdint>

namespace vesica::fp {

inline constexpr std::uint8_t kProtocolMajor = 1;
// Minor 1 adds the host-driven calibration session, the A/B calibration slots and their
// parameters (docs/protocol.md sections 9 and 11).
// Minor 2: the calibration session's own watchdog and speed bound, and the raw hand-sensor
// readout for the guided hand steps (section 11).
// Minor 3: calibration image layout 2 (section 9): the torque-constant correction, the roll sensor
// offset, the jaw handle's span and the pedal's travel are stored and used; a layout-1 image of an
// older tool still boots, its missing values neutral.
// Minor 4: homing after power-up (section 11): a node whose encoders lose their position when off
// flags "not homed" in its heartbeat and refuses Enable until a host has homed it (procedure Home).
inline constexpr std::uint8_t kProtocolMinor = 4;
inline constexpr std::uint8_t kHomingMinor = 4;
inline constexpr int kJointCount = 3;  // actuated joints per arm: yaw, pitch, insertion

// Node state machine (docs/protocol.md "Node state machine").
enum class NodeState : std::uint8_t { Boot = 0, PreOperational = 1, Operational = 2, Stopped = 3, Fault = 4 };
inline constexpr std::uint8_t kNodeStateCount = 5;

// CANopen heartbeat byte for each NodeState (CiA 301 7.2.8.3.2.1); Fault reports pre-operational.
constexpr std::uint8_t canopen_heartbeat_code(NodeState s) {
  switch (s) {
    case NodeState::Boot: return 0x00;
    case NodeState::Stopped: return 0x04;
    case NodeState::Operational: return 0x05;
    case NodeState::PreOperational:
    case NodeState::Fault: return 0x7F;
  }
  return 0x7F;
}

// Which limiter shaped the last current output (highest in this order wins the report).
enum class Limiter : std::uint8_t {
  None = 0, Current = 1, Torque = 2, Velocity = 3, JointRange = 4, Disabled = 5, Fault = 6
};
inline constexpr std::uint8_t kLimiterCount = 7;

// CANopen NMT command specifiers (CiA 301), unchanged.
enum class NmtCommand : std::uint8_t {
  Start = 0x01, Stop = 0x02, EnterPreOperational = 0x80, ResetNode = 0x81, ResetCommunication = 0x82
};

enum class ControlCommand : std::uint8_t { Enable = 1, Disable = 2, FaultReset = 3 };

enum class CommandMode : std::uint8_t { MotorCurrent = 0, JointTorque = 1 };

// Fault codes: our own byte, each mapped to a CiA 301/402 EMCY error code (fault_codes below).
enum class FaultCode : std::uint8_t {
  None = 0,
  CommandWatchdog = 1,
  EmergencyStop = 2,
  OverCurrent = 3,
  OverSpeed = 4,
  JointRangeExceeded = 5,
  ParameterCrc = 6,
  UnderVoltage = 7,
  OverVoltage = 8,
  OverTemperature = 9,
  ProtocolMismatch = 10,
};
inline constexpr std::uint8_t kFaultCodeCount = 11;

// CiA 301 / 402 emergency error codes our faults report.
constexpr std::uint16_t emcy_error_code(FaultCode f) {
  switch (f) {
    case FaultCode::None: return 0x0000;               // error reset / no error
    case FaultCode::CommandWatchdog: return 0x8130;    // life guard / heartbeat error
    case FaultCode::EmergencyStop: return 0x5441;      // drive disabled by enable/stop input
    case FaultCode::OverCurrent: return 0x2310;        // continuous over-current
    case FaultCode::OverSpeed: return 0x8400;          // velocity (speed controller)
    case FaultCode::JointRangeExceeded: return 0x8612; // reference (position) limit
    case FaultCode::ParameterCrc: return 0x5530;       // data storage (EEPROM)
    case FaultCode::UnderVoltage: return 0x3220;
    case FaultCode::OverVoltage: return 0x3210;
    case FaultCode::OverTemperature: return 0x4210;
    case FaultCode::ProtocolMismatch: return 0x8200;   // protocol error
  }
  return 0xFF00;
}

// CiA 301 error register bits (object 0x1001).
constexpr std::uint8_t emcy_error_register(FaultCode f) {
  switch (f) {
    case FaultCode::None: return 0x00;
    case FaultCode::OverCurrent: return 0x03;  // generic | current
    case FaultCode::UnderVoltage:
    case FaultCode::OverVoltage: return 0x05;  // generic | voltage
    case FaultCode::OverTemperature: return 0x09;  // generic | temperature
    case FaultCode::CommandWatchdog:
    case FaultCode::ProtocolMismatch: return 0x11;  // generic | communication
    default: return 0x81;  // generic | manufacturer specific
  }
}

enum class ParameterOp : std::uint8_t { Read = 1, Write = 2, Save = 3, RestoreDefaults = 4 };
enum class ParameterType : std::uint8_t { None = 0, U32 = 1, I32 = 2, F32 = 3 };

// Parameter-channel abort codes: CiA 301 SDO abort codes where one fits.
enum class AbortCode : std::uint32_t {
  None = 0,
  CommandInvalid = 0x05040001,
  ReadOnly = 0x06010002,
  NoSuchParameter = 0x06020000,
  TypeMismatch = 0x06070010,
  ValueTooHigh = 0x06090031,
  ValueTooLow = 0x06090032,
  StorageFailed = 0x08000020,
  WrongState = 0x08000022,
};

// Session (minor 1): the host drives the motors with CurrentCommand inside the node's calibration
// envelope; it ends in Save (kept) or anything else (the stored calibration is reloaded).
// HandSensors (protocol 1.2): inside a session, the node reports the raw roll, jaw handle and
// pedal sensor readings until the session ends (docs/protocol.md section 11).
// Home (protocol 1.4): inside a session, after the host found each joint's frame again (lower
// hard stop, then the reference index), it declares the position offsets in RAM this power-up's:
// the node is homed, and they outlive the session's end.
enum class CalibrationProcedure : std::uint8_t { Abort = 0, FindIndex = 1, CurrentOffset = 2, Session = 3, HandSensors = 4, Home = 5 };
enum class CalibrationStatus : std::uint8_t { Idle = 0, Running = 1, Done = 2, Failed = 3, Aborted = 4 };

const char* to_string(NodeState s);
const char* to_string(Limiter l);
const char* to_string(FaultCode f);

}  // namespace vesica::fp
