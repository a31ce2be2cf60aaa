#include "device/stylus/omni_datagram.h"

#include <bit>
#include <cstdio>
#include <cstring>

#include "device/stylus/stylus_state.h"

namespace vesica::device {
namespace {

namespace L = omni_layout;

template <typename T>
void PutLe(std::uint8_t* at, T value) {
  using U = std::conditional_t<sizeof(T) == 8, std::uint64_t,
                               std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint16_t>>;
  const U bits = std::bit_cast<U>(value);
  for (std::size_t i = 0; i < sizeof(U); ++i) at[i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

template <typename T>
T GetLe(const std::uint8_t* at) {
  using U = std::conditional_t<sizeof(T) == 8, std::uint64_t,
                               std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint16_t>>;
  U bits = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) bits |= static_cast<U>(static_cast<U>(at[i]) << (8 * i));
  return std::bit_cast<T>(bits);
}

void PutVector(std::uint8_t* at, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) PutLe(at + 8 * i, v[i]);
}

Eigen::Vector3d GetVector(const std::uint8_t* at) {
  return {GetLe<double>(at), GetLe<double>(at + 8), GetLe<double>(at + 16)};
}

void PutHeader(std::uint8_t* at, OmniDatagramKind kind, std::uint32_t sequence, std::uint32_t word12,
               std::int64_t timestamp_ns) {
  std::memcpy(at + L::kMagic, kOmniMagic.data(), kOmniMagic.size());
  at[L::kVersion] = kOmniProtocolVersion;
  at[L::kKind] = static_cast<std::uint8_t>(kind);
  PutLe<std::uint16_t>(at + L::kReserved, 0);
  PutLe(at + L::kSequence, sequence);
  PutLe(at + L::kWord12, word12);
  PutLe(at + L::kTimestamp, timestamp_ns);
}

const char* KindName(std::uint8_t kind) {
  switch (kind) {
    case static_cast<std::uint8_t>(OmniDatagramKind::kPose):
      return "pose";
    case static_cast<std::uint8_t>(OmniDatagramKind::kForce):
      return "force";
    default:
      return "unknown";
  }
}

// Checks what both kinds share; nullopt when the header says `kind` of this protocol version.
std::optional<std::string> HeaderProblem(std::span<const std::uint8_t> bytes, OmniDatagramKind kind, std::size_t size) {
  const char* want = KindName(static_cast<std::uint8_t>(kind));
  char buf[160];
  if (bytes.size() < L::kKind + 1 || std::memcmp(bytes.data(), kOmniMagic.data(), kOmniMagic.size()) != 0) {
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), kOmniMagic.data(), kOmniMagic.size()) == 0) {
      std::snprintf(buf, sizeof buf, "Omni datagram: %zu bytes, too short for a header (a %s datagram is %zu)",
                    bytes.size(), want, size);
    } else {
      std::snprintf(buf, sizeof buf, "Omni datagram: %zu bytes without the magic 'VOMN' at offset 0: not ours",
                    bytes.size());
    }
    return std::string(buf);
  }
  if (bytes[L::kVersion] != kOmniProtocolVersion) {
    std::snprintf(buf, sizeof buf, "Omni datagram: protocol version %u, this build speaks version %u",
                  bytes[L::kVersion], kOmniProtocolVersion);
    return std::string(buf);
  }
  if (bytes[L::kKind] != static_cast<std::uint8_t>(kind)) {
    std::snprintf(buf, sizeof buf, "Omni datagram: kind %u (%s) where a %s datagram was expected", bytes[L::kKind],
                  KindName(bytes[L::kKind]), want);
    return std::string(buf);
  }
  if (bytes.size() != size) {
    std::snprintf(buf, sizeof buf, "Omni %s datagram: %zu bytes, a version %u %s datagram is exactly %zu", want,
                  bytes.size(), kOmniProtocolVersion, want, size);
    return std::string(buf);
  }
  if (GetLe<std::uint16_t>(bytes.data() + L::kReserved) != 0) {
    std::snprintf(buf, sizeof buf, "Omni %s datagram: reserved field (offset 6) is 0x%04x, must be 0", want,
                  GetLe<std::uint16_t>(bytes.data() + L::kReserved));
    return std::string(buf);
  }
  return std::nullopt;
}

}  // namespace

OmniPoseBytes EncodeOmniPose(const OmniPoseDatagram& pose) {
  OmniPoseBytes bytes{};
  PutHeader(bytes.data(), OmniDatagramKind::kPose, pose.sequence, pose.buttons, pose.timestamp_ns);
  PutVector(bytes.data() + L::kVector0, pose.p_BTip_B);
  PutVector(bytes.data() + L::kVector1, pose.d_B);
  return bytes;
}

OmniForceBytes EncodeOmniForce(const OmniForceDatagram& force) {
  OmniForceBytes bytes{};
  PutHeader(bytes.data(), OmniDatagramKind::kForce, force.sequence, force.pose_sequence, force.timestamp_ns);
  PutVector(bytes.data() + L::kVector0, force.f_B);
  return bytes;
}

std::optional<std::string> DecodeOmniPose(std::span<const std::uint8_t> bytes, OmniPoseDatagram* out) {
  if (auto problem = HeaderProblem(bytes, OmniDatagramKind::kPose, L::kPoseSize)) return problem;
  OmniPoseDatagram pose;
  pose.sequence = GetLe<std::uint32_t>(bytes.data() + L::kSequence);
  pose.buttons = GetLe<std::uint32_t>(bytes.data() + L::kWord12);
  pose.timestamp_ns = GetLe<std::int64_t>(bytes.data() + L::kTimestamp);
  pose.p_BTip_B = GetVector(bytes.data() + L::kVector0);
  pose.d_B = GetVector(bytes.data() + L::kVector1);
  StylusState state;
  state.p_BTip_B = pose.p_BTip_B;
  state.d_B = pose.d_B;
  state.buttons = pose.buttons;
  if (auto problem = StylusStateProblem(state)) {
    return "Omni pose datagram (sequence " + std::to_string(pose.sequence) + "): " + *problem;
  }
  *out = pose;
  return std::nullopt;
}

std::optional<std::string> DecodeOmniForce(std::span<const std::uint8_t> bytes, OmniForceDatagram* out) {
  if (auto problem = HeaderProblem(bytes, OmniDatagramKind::kForce, L::kForceSize)) return problem;
  OmniForceDatagram force;
  force.sequence = GetLe<std::uint32_t>(bytes.data() + L::kSequence);
  force.pose_sequence = GetLe<std::uint32_t>(bytes.data() + L::kWord12);
  force.timestamp_ns = GetLe<std::int64_t>(bytes.data() + L::kTimestamp);
  force.f_B = GetVector(bytes.data() + L::kVector0);
  if (!force.f_B.allFinite()) {
    return "Omni force datagram (sequence " + std::to_string(force.sequence) + "): force is not finite";
  }
  *out = force;
  return std::nullopt;
}

}  // namespace vesica::device
