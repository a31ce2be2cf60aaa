#pragma once
// The Omni emulator's datagram protocol, version 1 (docs/omni.md): one UDP datagram each way per
// servo cycle on loopback. Device -> host: pose (P, D, buttons, sequence, device timestamp).
// Host -> device: force (F, sequence, the pose sequence it answers, host timestamp). Fixed-size,
// little-endian, no padding; the layouts below are the only definition (encoder, decoder and the
// documentation table follow them).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace vesica::device {

inline constexpr std::array<std::uint8_t, 4> kOmniMagic = {'V', 'O', 'M', 'N'};
inline constexpr std::uint8_t kOmniProtocolVersion = 1;

enum class OmniDatagramKind : std::uint8_t { kPose = 1, kForce = 2 };

/// Byte layout of both datagrams: offsets of each field.
namespace omni_layout {
inline constexpr std::size_t kMagic = 0;       // 4 bytes "VOMN"
inline constexpr std::size_t kVersion = 4;     // u8
inline constexpr std::size_t kKind = 5;        // u8 OmniDatagramKind
inline constexpr std::size_t kReserved = 6;    // u16, 0
inline constexpr std::size_t kSequence = 8;    // u32, +1 per datagram of that kind, wraps
inline constexpr std::size_t kWord12 = 12;     // u32: pose: buttons; force: answered pose sequence
inline constexpr std::size_t kTimestamp = 16;  // i64 ns, sender's CLOCK_MONOTONIC
inline constexpr std::size_t kVector0 = 24;    // 3 x f64: pose: p_BTip_B (m); force: f_B (N)
inline constexpr std::size_t kVector1 = 48;    // 3 x f64: pose only: d_B (unit)
inline constexpr std::size_t kPoseSize = 72;
inline constexpr std::size_t kForceSize = 48;
}  // namespace omni_layout

struct OmniPoseDatagram {
  std::uint32_t sequence = 0;
  std::uint32_t buttons = 0;
  std::int64_t timestamp_ns = 0;
  Eigen::Vector3d p_BTip_B = Eigen::Vector3d::Zero();  ///< m
  Eigen::Vector3d d_B = -Eigen::Vector3d::UnitZ();     ///< unit (the decoder checks non-zero)
};

struct OmniForceDatagram {
  std::uint32_t sequence = 0;
  std::uint32_t pose_sequence = 0;  ///< the latest pose the host had when it computed the force
  std::int64_t timestamp_ns = 0;
  Eigen::Vector3d f_B = Eigen::Vector3d::Zero();  ///< N, on the user's hand
};

using OmniPoseBytes = std::array<std::uint8_t, omni_layout::kPoseSize>;
using OmniForceBytes = std::array<std::uint8_t, omni_layout::kForceSize>;

OmniPoseBytes EncodeOmniPose(const OmniPoseDatagram& pose);
OmniForceBytes EncodeOmniForce(const OmniForceDatagram& force);

/// Decodes a pose datagram into *out. On any problem returns what is wrong (too short or long,
/// wrong magic, another protocol version, a force datagram, reserved bits set, a non-finite
/// value, a direction of zero length, unknown button bits) and leaves *out untouched.
std::optional<std::string> DecodeOmniPose(std::span<const std::uint8_t> bytes, OmniPoseDatagram* out);
/// The same for a force datagram (non-finite force included).
std::optional<std::string> DecodeOmniForce(std::span<const std::uint8_t> bytes, OmniForceDatagram* out);

}  // namespace vesica::device
