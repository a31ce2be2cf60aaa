#pragma once
// The calibration commands' ToolUi (app/calibrate/tool_ui.h) for the trainer's panel: called on
// the panel's worker thread, it hands each call to the panel's GUI thread (queued, never
// blocking it). The motion prompt waits for the person's answer on the worker thread and gives
// up (no) when the abort flag is set, so closing the panel never deadlocks with a prompt.

#include <atomic>
#include <functional>
#include <string>

#include "app/calibrate/tool_ui.h"

class QObject;

namespace vesica::app {

struct CalibrationPanelHandlers {
  std::function<void(int arm, const std::string& step, double fraction, double eta_s)> progress;
  std::function<void(const std::string& line)> note;
  /// Shows the question; calls `answer` exactly once (on the GUI thread) with the person's reply.
  std::function<void(const calibrate::MotionNotice& notice, std::function<void(bool)> answer)> ask;
};

class CalibrationPanelUi final : public calibrate::ToolUi {
 public:
  /// The handlers run on `gui`'s thread, and not at all once `gui` is deleted.
  CalibrationPanelUi(QObject* gui, CalibrationPanelHandlers handlers, const std::atomic<bool>* abort);
  void Progress(int arm, const std::string& step, double fraction, double eta_s) override;
  bool ConfirmMotion(const calibrate::MotionNotice& notice) override;
  void Note(const std::string& line) override;

 private:
  QObject* gui_;
  CalibrationPanelHandlers handlers_;
  const std::atomic<bool>* abort_;
};

/// The terminal's prompt in a panel's words: what moves, the current limit, how to stop.
std::string MotionQuestion(const calibrate::MotionNotice& notice);

}  // namespace vesica::app
