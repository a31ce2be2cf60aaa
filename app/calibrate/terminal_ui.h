// The terminal's side of the commands: progress bars with a time estimate on a terminal, plain
// lines when the output is not one (a log, a pipe), and the y/N prompt before an arm moves.
// Everything goes to stderr, so --json's stdout stays one JSON document.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "app/calibrate/tool_ui.h"

namespace vesica::app::calibrate {

class TerminalUi final : public ToolUi {
 public:
  /// assume_yes: --yes (scripts); quiet: notes and progress not shown (prompts still are).
  TerminalUi(bool assume_yes, bool quiet);
  ~TerminalUi() override;
  void Progress(int arm, const std::string& step, double fraction, double eta_s) override;
  bool ConfirmMotion(const MotionNotice& notice) override;
  void Note(const std::string& line) override;
  /// The prompt and the live value on one line, redrawn (a terminal) or a line a second (not one);
  /// Enter accepts, "r" Enter retries, "q" Enter stops. With --yes nobody is there: it declines.
  HandAnswer GuideHand(const HandPrompt& prompt, double live_value) override;

 private:
  void EndBar();
  /// A line typed on stdin so far, without blocking; true when one ended (Enter), false at no input.
  bool PollLine(std::string* line, bool* closed);

  bool assume_yes_;
  bool quiet_;
  bool tty_;
  bool bar_open_ = false;
  std::string step_;
  int last_quarter_ = -1;
  std::string hand_key_;  ///< the prompt on screen
  std::string typed_;     ///< stdin since the last Enter
  std::chrono::steady_clock::time_point hand_shown_{};
};

/// "1:05", "0:07", "--:--" for unknown.
std::string FormatEta(double seconds);

}  // namespace vesica::app::calibrate
