#pragma once
// What a 6-DOF stylus (Phantom Omni style) reports: tip position P, stylus direction D, two
// buttons. Plain data shared by every stylus backend and the needle physics that reads it.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "device/haptic_device.h"

namespace vesica::device {

/// Bits of StylusState::buttons.
inline constexpr std::uint32_t kStylusButton1 = 1u << 0;  ///< front (grey) button on an Omni: biopsy
inline constexpr std::uint32_t kStylusButton2 = 1u << 1;  ///< back (white) button on an Omni
inline constexpr std::uint32_t kStylusButtonMask = kStylusButton1 | kStylusButton2;

/// One sample of a stylus, in the device base frame B (Omni convention: x to the user's right,
/// y up, z toward the user; origin at the workspace centre).
struct StylusState {
  Eigen::Vector3d p_BTip_B = Eigen::Vector3d::Zero();  ///< tip position, m
  Eigen::Vector3d d_B = -Eigen::Vector3d::UnitZ();     ///< unit vector from the grip toward the tip
  std::uint32_t buttons = 0;                           ///< kStylusButton1 | kStylusButton2
  std::int64_t timestamp_ns = 0;                       ///< device clock of the sample
};

/// Directions shorter than this are "of zero length": they carry no direction to normalise.
inline constexpr double kMinDirectionNorm = 1e-6;

/// What is wrong with a pose as input (non-finite position or direction, a direction of zero
/// length, button bits beyond the two buttons), or nullopt when it is usable. The message names
/// the field and its value. A direction that is not unit but long enough is fine: NormalizedStylus
/// makes it unit.
std::optional<std::string> StylusStateProblem(const StylusState& state);

/// `state` with d_B made unit. Precondition: StylusStateProblem(state) is nullopt.
StylusState NormalizedStylus(StylusState state);

/// The stylus as a ToolState: R_BTip's z axis is D (the tool's axis toward its tip, as for the
/// laparoscopic instruments), x and y completed by the smallest rotation from B's z to D.
ToolState ToolStateFromStylus(const StylusState& state);

}  // namespace vesica::device
