#include "device/stylus/stylus_state.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

namespace vesica::device {
namespace {

std::string VectorText(const Eigen::Vector3d& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", v.x(), v.y(), v.z());
  return buf;
}

}  // namespace

std::optional<std::string> StylusStateProblem(const StylusState& state) {
  if (!state.p_BTip_B.allFinite()) return "stylus position " + VectorText(state.p_BTip_B) + " m is not finite";
  if (!state.d_B.allFinite()) return "stylus direction " + VectorText(state.d_B) + " is not finite";
  if (state.d_B.norm() < kMinDirectionNorm) {
    return "stylus direction " + VectorText(state.d_B) + " has zero length (a direction needs a norm >= 1e-6)";
  }
  if ((state.buttons & ~kStylusButtonMask) != 0) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "stylus buttons 0x%x use bits beyond the two buttons (mask 0x3)", state.buttons);
    return std::string(buf);
  }
  return std::nullopt;
}

StylusState NormalizedStylus(StylusState state) {
  // A direction already unit to rounding is kept bit for bit (recordings round-trip exactly).
  if (std::abs(state.d_B.norm() - 1.0) > 1e-12) state.d_B.normalize();
  return state;
}

ToolState ToolStateFromStylus(const StylusState& state) {
  ToolState tool;
  tool.p_BTip_B = state.p_BTip_B;
  tool.R_BTip = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), state.d_B.normalized()).toRotationMatrix();
  tool.buttons = state.buttons;
  tool.timestamp_ns = state.timestamp_ns;
  return tool;
}

}  // namespace vesica::device
