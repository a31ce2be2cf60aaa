#pragma once
// The calibration commands' ToolUi (app/calibrate/tool_ui.h) for the trainer's panel: called on
// the panel's worker thread, it hands each call to the panel's GUI thread (queued, never
// blocking it). The motion prompt waits for the person's answer on the worker thread and gives
// up (no) when the abort flag is set, so closing the panel never deadlocks with a prompt.

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

#include "app/calibrate/tool_ui.h"

class QObject;

namespace vesica::app {

struct CalibrationPanelHandlers {
  std::function<void(int arm, const std::string& step, double fraction, double eta_s)> progress;
  std::function<void(const std::string& line)> note;
  /// Shows the question; calls `answer` exactly once (on the GUI thread) with the person's reply.
  std::function<void(const calibrate::MotionNotice& notice, std::function<void(bool)> answer)> ask;
  /// A guided hand motion's prompt is new (first show, next prompt, or a retry).
  std::function<void(const calibrate::HandPrompt& prompt)> hand_prompt;
  /// The prompt's sensor, live (at most ten times a second).
  std::function<void(const calibrate::HandPrompt& prompt, double live_value)> hand_live;
};

class CalibrationPanelUi final : public calibrate::ToolUi {
 public:
  /// The handlers run on `gui`'s thread, and not at all once `gui` is deleted.
  CalibrationPanelUi(QObject* gui, CalibrationPanelHandlers handlers, const std::atomic<bool>* abort);
  void Progress(int arm, const std::string& step, double fraction, double eta_s) override;
  bool ConfirmMotion(const calibrate::MotionNotice& notice) override;
  void Note(const std::string& line) override;
  /// Never blocks: kWait until the person answers (HandAnswered), kAbort once the flag is set.
  calibrate::HandAnswer GuideHand(const calibrate::HandPrompt& prompt, double live_value) override;
  /// The GUI's answer to the prompt shown (Accept, Retry); taken by the next GuideHand call.
  void HandAnswered(calibrate::HandAnswer answer);

 private:
  QObject* gui_;
  CalibrationPanelHandlers handlers_;
  const std::atomic<bool>* abort_;
  std::mutex hand_mutex_;
  std::string hand_key_;  // step/prompt/attempt of the prompt shown
  std::optional<calibrate::HandAnswer> hand_answer_;
  std::chrono::steady_clock::time_point hand_shown_{};
};

/// The terminal's prompt in a panel's words: what moves, the current limit, how to stop.
std::string MotionQuestion(const calibrate::MotionNotice& notice);

}  // namespace vesica::app
