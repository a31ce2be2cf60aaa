#include "app/trainer/calibration_panel_ui.h"

#include <QMetaObject>
#include <QObject>
#include <chrono>
#include <cstdio>
#include <future>
#include <memory>

namespace vesica::app {

CalibrationPanelUi::CalibrationPanelUi(QObject* gui, CalibrationPanelHandlers handlers, const std::atomic<bool>* abort)
    : gui_(gui), handlers_(std::move(handlers)), abort_(abort) {}

void CalibrationPanelUi::Progress(int arm, const std::string& step, double fraction, double eta_s) {
  QMetaObject::invokeMethod(
      gui_, [h = handlers_.progress, arm, step, fraction, eta_s] { h(arm, step, fraction, eta_s); },
      Qt::QueuedConnection);
}

void CalibrationPanelUi::Note(const std::string& line) {
  QMetaObject::invokeMethod(
      gui_, [h = handlers_.note, line] { h(line); }, Qt::QueuedConnection);
}

bool CalibrationPanelUi::ConfirmMotion(const calibrate::MotionNotice& notice) {
  // The answer comes back through a promise; answered once even if the box reports twice.
  auto reply = std::make_shared<std::promise<bool>>();
  auto answered = std::make_shared<std::atomic<bool>>(false);
  std::future<bool> answer = reply->get_future();
  QMetaObject::invokeMethod(
      gui_,
      [h = handlers_.ask, notice, reply, answered] {
        h(notice, [reply, answered](bool yes) {
          if (!answered->exchange(true)) reply->set_value(yes);
        });
      },
      Qt::QueuedConnection);
  // The link is idle while a person reads (no calibration session is open yet).
  while (answer.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready)
    if (abort_ && abort_->load()) return false;
  return answer.get();
}

calibrate::HandAnswer CalibrationPanelUi::GuideHand(const calibrate::HandPrompt& prompt, double live_value) {
  if (abort_ && abort_->load()) return calibrate::HandAnswer::kAbort;
  const std::string key =
      prompt.step + "/" + std::to_string(prompt.prompt_index) + "/" + std::to_string(prompt.attempt);
  const auto now = std::chrono::steady_clock::now();
  bool fresh = false, show_live = false;
  std::optional<calibrate::HandAnswer> answer;
  {
    std::lock_guard<std::mutex> lock(hand_mutex_);
    if (key != hand_key_) {  // an answer given to the previous prompt is not this one's
      hand_key_ = key;
      hand_answer_.reset();
      hand_shown_ = {};
      fresh = true;
    }
    answer.swap(hand_answer_);
    if (now - hand_shown_ >= std::chrono::milliseconds(100)) {
      hand_shown_ = now;
      show_live = true;
    }
  }
  if (fresh)
    QMetaObject::invokeMethod(
        gui_, [h = handlers_.hand_prompt, prompt] { h(prompt); }, Qt::QueuedConnection);
  if (show_live || answer)
    QMetaObject::invokeMethod(
        gui_, [h = handlers_.hand_live, prompt, live_value] { h(prompt, live_value); }, Qt::QueuedConnection);
  return answer.value_or(calibrate::HandAnswer::kWait);
}

void CalibrationPanelUi::HandAnswered(calibrate::HandAnswer answer) {
  std::lock_guard<std::mutex> lock(hand_mutex_);
  hand_answer_ = answer;
}

std::string MotionQuestion(const calibrate::MotionNotice& notice) {
  std::string text = notice.arm_text + " will move:\n";
  for (const std::string& m : notice.motions) text += "  - " + m + "\n";
  char limit[64];
  std::snprintf(limit, sizeof limit, "%.2f A", notice.max_current_A);
  text += "\nEvery motion is slow and limited to " + std::string(limit) +
          ". Keep hands and instruments clear of the arm; Abort stops it at once.\n\nContinue?";
  return text;
}

}  // namespace vesica::app
