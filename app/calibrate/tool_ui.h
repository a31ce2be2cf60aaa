// What the calibration commands ask of whoever runs them: the terminal (terminal_ui.h) or the
// trainer's Tools > Calibrate panel. Called on the thread that runs the command.
#pragma once

#include <string>
#include <vector>

namespace vesica::app::calibrate {

/// Told before anything moves: which arm, what each step will do, the current limit.
struct MotionNotice {
  int arm = 0;
  std::string arm_text;              ///< "arm 1 (node 1, serial 0x5E51CA01)"
  std::vector<std::string> motions;  ///< one line per moving step
  double max_current_A = 0.0;
};

/// One prompt of a guided hand motion (roll sensor offset, jaw handle span, pedal travel): the
/// person moves a part of the handle by hand while the sensor's raw value is shown live, then
/// accepts the value or tries again. Motors are off during these steps.
struct HandPrompt {
  int arm = 0;
  std::string arm_text;      ///< "arm 1 (node 1, serial 0x5E51CA01)"
  std::string step;          ///< "jaw span", "pedal travel", "roll offset"
  std::string instruction;   ///< "Move the jaw handle to fully open and hold it there."
  std::string unit;          ///< the live value's unit: "counts"
  int prompt_index = 0;      ///< 0-based among the step's prompts (open, then closed: 0, 1)
  int prompt_count = 1;      ///< how many prompts the step has
  int attempt = 1;           ///< 1 on the first try, one more on each retry
  std::string retry_reason;  ///< why the previous try was not taken; "" on the first try
};

/// What the person answered to a HandPrompt.
enum class HandAnswer {
  kWait,    ///< still moving: show the next live value
  kAccept,  ///< take the live value just shown
  kRetry,   ///< start the step's prompts again (attempt + 1)
  kAbort,   ///< stop the command (arm left disabled, previous calibration in force)
};

class ToolUi {
 public:
  virtual ~ToolUi() = default;
  /// `step` of `arm` is `fraction` done (0..1); eta_s < 0 while unknown.
  virtual void Progress(int arm, const std::string& step, double fraction, double eta_s) = 0;
  /// Asked before a step moves the arm; false: nothing moves and the command ends aborted.
  /// The link is idle meanwhile (no session open), so it may wait for a person.
  virtual bool ConfirmMotion(const MotionNotice& notice) = 0;
  /// A line for the person (what is happening, what was found).
  virtual void Note(const std::string& line) = 0;
  /// Called again and again (about every 20 ms of bus time) while a guided hand step waits for
  /// the person, with the sensor's latest raw value; the step takes `live_value` on kAccept.
  /// Must not block for long (the link is serviced between calls): a panel returns kWait until
  /// a button is pressed. The default, for a UI that cannot show a live value, declines (kAbort):
  /// the command ends aborted, saying that the step needs a person at an interactive UI.
  virtual HandAnswer GuideHand(const HandPrompt& prompt, double live_value) {
    (void)prompt;
    (void)live_value;
    return HandAnswer::kAbort;
  }
};

/// Every notice answered yes, nothing shown (tests, --yes with --json).
class SilentUi final : public ToolUi {
 public:
  void Progress(int, const std::string&, double, double) override {}
  bool ConfirmMotion(const MotionNotice&) override { return true; }
  void Note(const std::string&) override {}
};

}  // namespace vesica::app::calibrate
