#pragma once
// The debrief screen of the Calot step (issue 36): shown after the critical error or at the
// case's end, it states the outcome, what went wrong and the metrics (debrief_text.h). A plain
// widget with no dependency on the trainer: the trainer shows it (as a page or a window) and
// connects CloseButton()'s clicked() to what comes next. Parts have objectNames for tests:
// "debrief_title", "debrief_outcome", "debrief_reasons", "debrief_metrics" (a QFormLayout's
// widget; value labels "debrief_value_<row>"), "debrief_close".

#include <QWidget>

#include "app/calot/debrief_text.h"

class QFormLayout;
class QLabel;
class QPushButton;

namespace vesica::app::calot {

class DebriefScreen : public QWidget {
 public:
  explicit DebriefScreen(QWidget* parent = nullptr);

  /// Shows this debrief (replacing what was shown).
  void Show(const DebriefText& text);
  /// Shows the debrief of the case as it stands.
  void Show(const CalotMetrics& metrics) { Show(MakeDebriefText(metrics)); }

  /// Everything the screen says, top to bottom, one line each ("Critical view of safety: not
  /// reached"), for tests and for logging the debrief.
  QString AllText() const;

  QLabel* Outcome() const { return outcome_; }
  QLabel* Reasons() const { return reasons_; }
  QPushButton* CloseButton() const { return close_; }

 private:
  QLabel* title_ = nullptr;
  QLabel* outcome_ = nullptr;
  QLabel* reasons_ = nullptr;
  QWidget* metrics_box_ = nullptr;
  QFormLayout* metrics_ = nullptr;
  QPushButton* close_ = nullptr;
};

}  // namespace vesica::app::calot
