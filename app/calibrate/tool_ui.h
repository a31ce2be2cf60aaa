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
};

/// Every notice answered yes, nothing shown (tests, --yes with --json).
class SilentUi final : public ToolUi {
 public:
  void Progress(int, const std::string&, double, double) override {}
  bool ConfirmMotion(const MotionNotice&) override { return true; }
  void Note(const std::string&) override {}
};

}  // namespace vesica::app::calibrate
