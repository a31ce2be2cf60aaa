#include "app/calibrate/terminal_ui.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace vesica::app::calibrate {

std::string FormatEta(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "--:--";
  const long s = std::lround(seconds);
  char b[32];
  std::snprintf(b, sizeof b, "%ld:%02ld", s / 60, s % 60);
  return b;
}

TerminalUi::TerminalUi(bool assume_yes, bool quiet)
    : assume_yes_(assume_yes), quiet_(quiet), tty_(isatty(STDERR_FILENO) == 1) {}

TerminalUi::~TerminalUi() { EndBar(); }

void TerminalUi::EndBar() {
  if (bar_open_) std::fputc('\n', stderr);
  bar_open_ = false;
}

void TerminalUi::Progress(int arm, const std::string& step, double fraction, double eta_s) {
  if (quiet_) return;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const bool new_step = step != step_;
  if (new_step) {
    EndBar();
    step_ = step;
    last_quarter_ = -1;
  }
  if (tty_) {
    // One bar redrawn in place: 30 cells, the percentage and the time left.
    const int cells = static_cast<int>(std::lround(30 * fraction));
    std::fprintf(stderr, "\r  arm %d %-18s [%s%s] %3d%%  %s left ", arm, step.c_str(), std::string(cells, '#').c_str(),
                 std::string(30 - cells, '.').c_str(), static_cast<int>(std::lround(100 * fraction)),
                 FormatEta(eta_s).c_str());
    std::fflush(stderr);
    bar_open_ = true;
    if (fraction >= 1.0) EndBar();
    return;
  }
  // Not a terminal: a line at the start, at each quarter and at the end.
  const int quarter = static_cast<int>(std::floor(4 * fraction));
  if (quarter == last_quarter_) return;
  last_quarter_ = quarter;
  std::fprintf(stderr, "arm %d %s: %d%% (%s left)\n", arm, step.c_str(), static_cast<int>(std::lround(100 * fraction)),
               FormatEta(eta_s).c_str());
}

bool TerminalUi::ConfirmMotion(const MotionNotice& notice) {
  EndBar();
  std::string text = notice.arm_text + " will move:\n";
  for (const std::string& m : notice.motions) text += "  - " + m + "\n";
  char limit[64];
  std::snprintf(limit, sizeof limit, "%.2f A", notice.max_current_A);
  text += "  every motion slow and limited to " + std::string(limit) +
          "; keep hands and instruments clear of the arm; Ctrl-C stops it.\n";
  std::fputs(text.c_str(), stderr);
  if (assume_yes_) {
    std::fprintf(stderr, "continue? [y/N] y (--yes)\n");
    return true;
  }
  std::fprintf(stderr, "continue? [y/N] ");
  std::fflush(stderr);
  std::string answer;
  if (!std::getline(std::cin, answer)) {
    std::fputc('\n', stderr);
    return false;  // no one to answer (stdin closed): nothing moves
  }
  return answer == "y" || answer == "Y" || answer == "yes";
}

bool TerminalUi::PollLine(std::string* line, bool* closed) {
  *closed = false;
  pollfd p{STDIN_FILENO, POLLIN, 0};
  while (poll(&p, 1, 0) == 1 && (p.revents & (POLLIN | POLLHUP))) {
    char c = 0;
    if (read(STDIN_FILENO, &c, 1) != 1) {
      *closed = true;
      return false;
    }
    if (c == '\n') {
      *line = typed_;
      typed_.clear();
      return true;
    }
    typed_ += c;
  }
  return false;
}

HandAnswer TerminalUi::GuideHand(const HandPrompt& prompt, double live_value) {
  if (assume_yes_) {
    EndBar();
    std::fprintf(stderr, "%s: %s needs a person at the arm to move it; --yes cannot: stopped\n",
                 prompt.arm_text.c_str(), prompt.step.c_str());
    return HandAnswer::kAbort;
  }
  const std::string key =
      prompt.step + "/" + std::to_string(prompt.prompt_index) + "/" + std::to_string(prompt.attempt);
  const auto now = std::chrono::steady_clock::now();
  if (key != hand_key_) {
    EndBar();
    hand_key_ = key;
    if (!prompt.retry_reason.empty()) std::fprintf(stderr, "  again (%s)\n", prompt.retry_reason.c_str());
    std::fprintf(stderr,
                 "arm %d %s (%d of %d%s): %s\n  Enter: take the value shown; r Enter: start this step again; q "
                 "Enter: stop\n",
                 prompt.arm, prompt.step.c_str(), prompt.prompt_index + 1, prompt.prompt_count,
                 prompt.attempt > 1 ? (", try " + std::to_string(prompt.attempt)).c_str() : "",
                 prompt.instruction.c_str());
    hand_shown_ = {};
  }
  // The live value: redrawn in place on a terminal, a line a second otherwise.
  if (now - hand_shown_ >= (tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(1000))) {
    hand_shown_ = now;
    std::fprintf(stderr, tty_ ? "\r  live: %6.0f %s   " : "  live: %.0f %s\n", live_value, prompt.unit.c_str());
    std::fflush(stderr);
    bar_open_ = tty_;
  }
  std::string line;
  bool closed = false;
  if (!PollLine(&line, &closed)) return closed ? HandAnswer::kAbort : HandAnswer::kWait;
  EndBar();
  if (line.empty()) return HandAnswer::kAccept;
  if (line == "r" || line == "R") return HandAnswer::kRetry;
  if (line == "q" || line == "Q") return HandAnswer::kAbort;
  std::fprintf(stderr, "  Enter, r or q\n");
  return HandAnswer::kWait;
}

void TerminalUi::Note(const std::string& line) {
  if (quiet_) return;
  EndBar();
  std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace vesica::app::calibrate
