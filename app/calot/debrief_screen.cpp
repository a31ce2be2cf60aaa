#include "app/calot/debrief_screen.h"

#include <QFormLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace vesica::app::calot {
namespace {

QString Text(const std::string& utf8) { return QString::fromStdString(utf8); }

}  // namespace

DebriefScreen::DebriefScreen(QWidget* parent) : QWidget(parent) {
  setWindowTitle(QStringLiteral("Vesica: Calot's triangle debrief"));
  title_ = new QLabel(this);
  title_->setObjectName(QStringLiteral("debrief_title"));
  QFont title_font = title_->font();
  title_font.setPointSizeF(title_font.pointSizeF() * 1.4);
  title_font.setBold(true);
  title_->setFont(title_font);
  outcome_ = new QLabel(this);
  outcome_->setObjectName(QStringLiteral("debrief_outcome"));
  QFont outcome_font = outcome_->font();
  outcome_font.setPointSizeF(outcome_font.pointSizeF() * 1.2);
  outcome_font.setBold(true);
  outcome_->setFont(outcome_font);
  reasons_ = new QLabel(this);
  reasons_->setObjectName(QStringLiteral("debrief_reasons"));
  reasons_->setWordWrap(true);
  reasons_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  metrics_box_ = new QWidget(this);
  metrics_box_->setObjectName(QStringLiteral("debrief_metrics"));
  metrics_ = new QFormLayout(metrics_box_);
  metrics_->setLabelAlignment(Qt::AlignRight);
  close_ = new QPushButton(QStringLiteral("Continue"), this);
  close_->setObjectName(QStringLiteral("debrief_close"));

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(title_);
  layout->addWidget(outcome_);
  layout->addWidget(reasons_);
  layout->addWidget(metrics_box_);
  layout->addStretch(1);
  layout->addWidget(close_, 0, Qt::AlignRight);
  resize(640, 480);
}

void DebriefScreen::Show(const DebriefText& text) {
  title_->setText(Text(text.title));
  outcome_->setText(Text(text.headline));
  // A failed case in red, a passed one in green: the first thing a trainee reads.
  outcome_->setStyleSheet(text.reasons.empty() ? QStringLiteral("color: #1b7f3b;") : QStringLiteral("color: #b00020;"));
  QStringList reasons;
  for (const std::string& reason : text.reasons) reasons << QString::fromUtf8("• ") + Text(reason);
  reasons_->setText(reasons.join('\n'));
  reasons_->setVisible(!reasons.isEmpty());
  while (metrics_->rowCount() > 0) metrics_->removeRow(0);
  for (std::size_t i = 0; i < text.metrics.size(); ++i) {
    auto* value = new QLabel(Text(text.metrics[i].second), metrics_box_);
    value->setObjectName(QStringLiteral("debrief_value_%1").arg(i));
    value->setTextInteractionFlags(Qt::TextSelectableByMouse);
    metrics_->addRow(Text(text.metrics[i].first) + ':', value);
  }
}

QString DebriefScreen::AllText() const {
  QStringList lines{title_->text(), outcome_->text()};
  if (!reasons_->text().isEmpty()) lines << reasons_->text();
  for (int row = 0; row < metrics_->rowCount(); ++row) {
    const auto* caption = qobject_cast<QLabel*>(metrics_->itemAt(row, QFormLayout::LabelRole)->widget());
    const auto* value = qobject_cast<QLabel*>(metrics_->itemAt(row, QFormLayout::FieldRole)->widget());
    lines << (caption ? caption->text() : QString()) + ' ' + (value ? value->text() : QString());
  }
  return lines.join('\n');
}

}  // namespace vesica::app::calot
