#pragma once
// The right hand's port during a case: which of its tools (the hook, the clip applier, the
// scissors) is in it now, and the exchange that brings the next. A keyboard key or the arm's
// handle button asks for it; the tool is part of each input frame, so recordings replay it.

#include <vector>

#include "app/scenario/scenario.h"
#include "physics/instrument/instrument_tool.h"

namespace vesica::app {

class ToolExchange {
 public:
  /// The hook alone.
  ToolExchange() : ToolExchange({physics::InstrumentTool::kCauteryHook}) {}
  /// `tools`: the mounted tool first, then the exchange order. Throws std::invalid_argument when
  /// empty, when it holds the grasper (its port keeps it) or a tool twice.
  explicit ToolExchange(std::vector<physics::InstrumentTool> tools);

  physics::InstrumentTool current() const { return tools_[index_]; }
  const std::vector<physics::InstrumentTool>& tools() const { return tools_; }

  /// Brings the next tool (after the last, the first again) and returns it. A port with one tool
  /// keeps it.
  physics::InstrumentTool Next();

  /// The handle button as sampled: a press (released -> pressed) exchanges once; holding it does
  /// not exchange again. Returns whether this sample exchanged.
  bool OnButton(bool pressed);

 private:
  std::vector<physics::InstrumentTool> tools_;
  std::size_t index_ = 0;
  bool button_was_pressed_ = false;
};

/// The right hand's port of `scenario`: its cautery hook, then its `exchange` list.
ToolExchange RightPortExchange(const Scenario& scenario);

}  // namespace vesica::app
