// What the reference firmware node needs from its board (moteus style: logic templated on hardware).
// Use: implement a class with these members (the arm emulator does; a microcontroller port would),
// then instantiate Node<YourHardware> (node.h). With C++20 the NodeHardware concept checks it.
// Freestanding C++17.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware_protocol/codec/messages.h"

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
#include <concepts>
#endif

namespace vesica::fp {

// One sample of the board's sensors, SI units, taken at the start of each control tick.
struct HardwareSample {
  JointArray position{};      // rad, rad, m (after calibration offsets are applied by the node)
  JointArray velocity{};      // rad/s, rad/s, m/s
  JointArray current{};       // A, measured motor currents (before offset correction)
  bool index_seen[kJointCount] = {};  // encoder index pulse seen since the last sample
  float roll_rad = 0;
  float jaw_rad = 0;
  bool pedal = false;
  bool handle_button = false;
  bool estop_input = false;   // hard-wired E-stop loop open
  float bus_V = 24;
  float board_temperature_degC = 25;
  // Raw counts of the hand sensors, as their converters give them (protocol 1.2's readout for the
  // guided hand calibration): roll's absolute encoder (0..16383 a turn), the jaw handle's and the
  // pedal's ADCs (0..4095).
  std::int32_t roll_raw = 0;
  std::int32_t jaw_raw = 0;
  std::int32_t pedal_raw = 0;
};

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
// sense(): read sensors. apply_currents(): command the current loops (A), zero = free.
// storage_read/storage_write(offset, ...): n bytes at a byte offset of the non-volatile memory that
// holds the two calibration slots (calibration_slot.h); a write erases what it covers first (a
// flash sector per slot) and may be cut by a power loss at any byte. False on failure.
template <class H>
concept NodeHardware = requires(H& h, const JointArray& amps, std::uint8_t* dst, const std::uint8_t* src,
                                std::size_t offset, std::size_t n) {
  { h.sense() } -> std::same_as<HardwareSample>;
  h.apply_currents(amps);
  { h.storage_read(offset, dst, n) } -> std::same_as<bool>;
  { h.storage_write(offset, src, n) } -> std::same_as<bool>;
};
#define VESICA_NODE_HARDWARE NodeHardware
#else
#define VESICA_NODE_HARDWARE typename
#endif

}  // namespace vesica::fp
