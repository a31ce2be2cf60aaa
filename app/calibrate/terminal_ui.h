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

 private:
  void EndBar();

  bool assume_yes_;
  bool quiet_;
  bool tty_;
  bool bar_open_ = false;
  std::string step_;
  int last_quarter_ = -1;
};

/// "1:05", "0:07", "--:--" for unknown.
std::string FormatEta(double seconds);

}  // namespace vesica::app::calibrate
