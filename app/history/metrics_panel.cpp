#include "app/history/metrics_panel.h"

#include <QFormLayout>
#include <QLabel>
#include <string>

#include "app/history/metric_format.h"

namespace vesica::app {
namespace {

// Row captions, in kMetricsPanelLabels order.
constexpr std::array<const char*, kMetricsPanelLabels.size()> kCaptions{
    "Time",       "Path length, grasper", "Path length, hook",  "Slips",
    "Cautery on", "Liver damage",         "Gallbladder damage", "Max force",
    "Mean force", "Tissue removed",       "Springs cut",        "Success"};

QString Placeholder() { return QString::fromUtf8("–"); }

QString WithUnit(const std::string& number, const char* unit) {
  return QString::fromStdString(number) + QString::fromUtf8(unit);
}

}  // namespace

MetricsPanel::MetricsPanel(QWidget* parent) : QWidget(parent) {
  auto* form = new QFormLayout(this);
  form->setLabelAlignment(Qt::AlignRight);
  for (std::size_t i = 0; i < values_.size(); ++i) {
    values_[i] = new QLabel(Placeholder(), this);
    values_[i]->setObjectName(QString::fromLatin1(kMetricsPanelLabels[i]));
    values_[i]->setTextInteractionFlags(Qt::TextSelectableByMouse);
    form->addRow(QString::fromLatin1(kCaptions[i]) + ":", values_[i]);
  }
}

void MetricsPanel::Show(const SessionMetrics& m) {
  const std::array<QString, kMetricsPanelLabels.size()> texts{
      QString::fromStdString(FormatMinutesSeconds(m.duration_s)),
      WithUnit(FormatCentimetres(m.path_length_left_m), " cm"),
      WithUnit(FormatCentimetres(m.path_length_right_m), " cm"),
      QString::number(m.slips),
      QString::fromStdString(FormatMinutesSeconds(m.cautery_on_s)),
      WithUnit(FormatSquareMillimetres(m.liver_damage_m2), " mm²"),
      WithUnit(FormatSquareMillimetres(m.gallbladder_damage_m2), " mm²"),
      WithUnit(FormatNewtons(m.max_force_N), " N"),
      WithUnit(FormatNewtons(m.mean_force_N), " N"),
      WithUnit(FormatPercent(m.tissue_removed_fraction), " %"),
      QStringLiteral("%1 / %2").arg(m.springs_cut).arg(m.springs_total),
      QString::fromStdString(FormatOutcome(m))};
  for (std::size_t i = 0; i < values_.size(); ++i) values_[i]->setText(texts[i]);
}

void MetricsPanel::Clear() {
  for (QLabel* value : values_) value->setText(Placeholder());
}

QString MetricsPanel::ValueText(const QString& object_name) const {
  for (const QLabel* value : values_)
    if (value->objectName() == object_name) return value->text();
  return {};
}

}  // namespace vesica::app
