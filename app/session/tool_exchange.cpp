#include "app/session/tool_exchange.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace vesica::app {

ToolExchange::ToolExchange(std::vector<physics::InstrumentTool> tools) : tools_(std::move(tools)) {
  if (tools_.empty()) throw std::invalid_argument("ToolExchange: a port needs a tool");
  for (std::size_t i = 0; i < tools_.size(); ++i) {
    if (!physics::IsRightHandTool(tools_[i]))
      throw std::invalid_argument("ToolExchange: the grasper stays in the left hand's port");
    if (std::find(tools_.begin(), tools_.begin() + static_cast<std::ptrdiff_t>(i), tools_[i]) !=
        tools_.begin() + static_cast<std::ptrdiff_t>(i))
      throw std::invalid_argument(std::string("ToolExchange: ") + physics::ToolKey(tools_[i]) + " listed twice");
  }
}

physics::InstrumentTool ToolExchange::Next() {
  index_ = (index_ + 1) % tools_.size();
  return current();
}

bool ToolExchange::OnButton(bool pressed) {
  const bool press = pressed && !button_was_pressed_;
  button_was_pressed_ = pressed;
  if (press && tools_.size() > 1) {
    Next();
    return true;
  }
  return false;
}

ToolExchange RightPortExchange(const Scenario& scenario) {
  for (const InstrumentConfig& c : scenario.instruments) {
    if (c.kind != InstrumentKind::kCauteryHook) continue;
    std::vector<physics::InstrumentTool> tools{c.kind};
    tools.insert(tools.end(), c.exchange.begin(), c.exchange.end());
    return ToolExchange(std::move(tools));
  }
  return ToolExchange();
}

}  // namespace vesica::app
