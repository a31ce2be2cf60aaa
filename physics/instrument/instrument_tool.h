#pragma once
// Which instrument a port holds. The left hand's port keeps the grasper; the right hand's port
// takes the cautery hook, the clip applier or the scissors, exchanged through the trocar during
// a case (Calot's triangle needs all three). One enum for the scenario, the input and the physics.

#include <optional>
#include <string_view>

namespace vesica::physics {

enum class InstrumentTool { kGrasper, kCauteryHook, kClipApplier, kScissors };

/// The key in scenarios and recordings: "grasper", "cautery_hook", "clip_applier", "scissors".
constexpr const char* ToolKey(InstrumentTool tool) {
  switch (tool) {
    case InstrumentTool::kGrasper:
      return "grasper";
    case InstrumentTool::kCauteryHook:
      return "cautery_hook";
    case InstrumentTool::kClipApplier:
      return "clip_applier";
    case InstrumentTool::kScissors:
      return "scissors";
  }
  return "grasper";
}

/// What a person reads on screen: "Grasper", "Hook", "Clip applier", "Scissors".
constexpr const char* ToolTitle(InstrumentTool tool) {
  switch (tool) {
    case InstrumentTool::kGrasper:
      return "Grasper";
    case InstrumentTool::kCauteryHook:
      return "Hook";
    case InstrumentTool::kClipApplier:
      return "Clip applier";
    case InstrumentTool::kScissors:
      return "Scissors";
  }
  return "Grasper";
}

/// The tool of a key; nullopt for anything else.
constexpr std::optional<InstrumentTool> ParseToolKey(std::string_view key) {
  for (InstrumentTool t : {InstrumentTool::kGrasper, InstrumentTool::kCauteryHook, InstrumentTool::kClipApplier,
                           InstrumentTool::kScissors})
    if (key == ToolKey(t)) return t;
  return std::nullopt;
}

/// Whether the right hand's port may hold `tool` (everything but the grasper, which the left
/// hand's port keeps: the scene's grasp state machine belongs to it).
constexpr bool IsRightHandTool(InstrumentTool tool) { return tool != InstrumentTool::kGrasper; }

}  // namespace vesica::physics
