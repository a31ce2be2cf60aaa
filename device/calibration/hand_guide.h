// The guided hand steps' conversation with the person (roll sensor offset, jaw handle span,
// pedal travel): a prompt, the sensor's raw value live, and the answer. The tool's ToolUi
// (app/calibrate/tool_ui.h) and tests' scripted hands implement it.
#pragma once

#include <functional>
#include <string>

namespace vesica::device::calibration {

struct HandPromptSpec {
  std::string step;         ///< "roll offset", "jaw span", "pedal travel"
  std::string instruction;  ///< "Open the jaw handle fully and hold it there."
  int prompt_index = 0;     ///< 0-based among the step's prompts
  int prompt_count = 1;
  int attempt = 1;           ///< 1, then one more on each retry
  std::string retry_reason;  ///< why the previous attempt was not taken ("" on the first)
};

enum class HandReply { kWait, kAccept, kRetry, kAbort };

/// Called every servo period (1 ms of bus time) while a prompt waits, with the sensor's latest
/// raw reading (counts); kAccept takes that reading.
using HandGuide = std::function<HandReply(const HandPromptSpec& prompt, double live_raw)>;

}  // namespace vesica::device::calibration
