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

constexpr std::array<const char*, kBiopsyPanelLabels.size()> kBiopsyCaptions{
    "Time to sample", "Sample to tumour centre", "Specimen", "No-go crossings", "Insertion attempts"};

constexpr std::array<const char*, kCalotPanelLabels.size()> kCalotCaptions{
    "Critical view of safety", "Clips, cystic duct", "Clips, cystic artery", "Division",
    "Bleeding events",         "Bile leaks",         "Bile duct injuries",   "Calot step"};

// Rows of kMetricsPanelLabels a biopsy shows too: time, max force, mean force, success.
bool SharedRow(std::size_t i) { return i == 0 || i == 7 || i == 8 || i == 11; }

QString Placeholder() { return QString::fromUtf8("–"); }

QString WithUnit(const std::string& number, const char* unit) {
  return QString::fromStdString(number) + QString::fromUtf8(unit);
}

}  // namespace

MetricsPanel::MetricsPanel(QWidget* parent) : QWidget(parent) {
  auto* form = new QFormLayout(this);
  form->setLabelAlignment(Qt::AlignRight);
  const auto add_row = [&](const char* name, const char* caption, QLabel*& value_label, QLabel*& caption_label) {
    value_label = new QLabel(Placeholder(), this);
    value_label->setObjectName(QString::fromLatin1(name));
    value_label->setTextInteractionFlags(Qt::TextSelectableByMouse);
    caption_label = new QLabel(QString::fromLatin1(caption) + ":", this);
    form->addRow(caption_label, value_label);
  };
  for (std::size_t i = 0; i < values_.size(); ++i)
    add_row(kMetricsPanelLabels[i], kCaptions[i], values_[i], captions_[i]);
  for (std::size_t i = 0; i < biopsy_values_.size(); ++i)
    add_row(kBiopsyPanelLabels[i], kBiopsyCaptions[i], biopsy_values_[i], biopsy_captions_[i]);
  for (std::size_t i = 0; i < calot_values_.size(); ++i)
    add_row(kCalotPanelLabels[i], kCalotCaptions[i], calot_values_[i], calot_captions_[i]);
  ShowRowsOf(Procedure::kCholecystectomy, false);
}

void MetricsPanel::ShowRowsOf(Procedure procedure, bool calot_step) {
  const bool biopsy = procedure == Procedure::kNeedleBiopsy;
  for (std::size_t i = 0; i < values_.size(); ++i) {
    const bool shown = !biopsy || SharedRow(i);
    values_[i]->setVisible(shown);
    captions_[i]->setVisible(shown);
  }
  for (std::size_t i = 0; i < biopsy_values_.size(); ++i) {
    biopsy_values_[i]->setVisible(biopsy);
    biopsy_captions_[i]->setVisible(biopsy);
  }
  for (std::size_t i = 0; i < calot_values_.size(); ++i) {
    calot_values_[i]->setVisible(!biopsy && calot_step);
    calot_captions_[i]->setVisible(!biopsy && calot_step);
  }
}

bool MetricsPanel::RowShown(const QString& object_name) const {
  const QLabel* label = findChild<QLabel*>(object_name);
  return label != nullptr && !label->isHidden();
}

void MetricsPanel::Show(const SessionMetrics& m, Procedure procedure) {
  ShowRowsOf(procedure, m.calot_step);
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
      QString::fromStdString(procedure == Procedure::kNeedleBiopsy ? FormatBiopsyOutcome(m) : FormatOutcome(m))};
  for (std::size_t i = 0; i < values_.size(); ++i) values_[i]->setText(texts[i]);
  const bool sampled = m.biopsy_sampled;
  const std::array<QString, kBiopsyPanelLabels.size()> biopsy_texts{
      sampled ? QString::fromStdString(FormatMinutesSeconds(m.time_to_sample_s)) : Placeholder(),
      sampled ? WithUnit(FormatMillimetres(m.sample_distance_m), " mm") : Placeholder(),
      sampled ? QString::fromStdString(FormatSpecimen(m.sample_distance_m)) : QStringLiteral("no sample"),
      QString::number(m.nogo_crossings), QString::number(m.insertion_attempts)};
  for (std::size_t i = 0; i < biopsy_values_.size(); ++i) biopsy_values_[i]->setText(biopsy_texts[i]);
  const std::array<QString, kCalotPanelLabels.size()> calot_texts{
      QString::fromStdString(FormatCriticalView(m)),
      QString::fromStdString(FormatClips(m.cystic_duct_clips, m.cystic_duct_clips_correct)),
      QString::fromStdString(FormatClips(m.cystic_artery_clips, m.cystic_artery_clips_correct)),
      QString::fromStdString(FormatDivision(m)),
      QString::number(m.bleeding_events),
      QString::number(m.bile_leaks),
      QString::number(m.bile_duct_injuries),
      QString::fromStdString(FormatCalotOutcome(m))};
  for (std::size_t i = 0; i < calot_values_.size(); ++i)
    calot_values_[i]->setText(m.calot_step ? calot_texts[i] : Placeholder());
}

void MetricsPanel::Clear() {
  for (QLabel* value : values_) value->setText(Placeholder());
  for (QLabel* value : biopsy_values_) value->setText(Placeholder());
  for (QLabel* value : calot_values_) value->setText(Placeholder());
}

QString MetricsPanel::ValueText(const QString& object_name) const {
  const QLabel* label = findChild<QLabel*>(object_name);
  return label != nullptr ? label->text() : QString();
}

}  // namespace vesica::app
