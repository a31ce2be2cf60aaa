#include "app/history/metrics_panel.h"

#include <gtest/gtest.h>

#include <QLabel>
#include <QRegularExpression>

namespace vesica::app {
namespace {

QString LabelText(const MetricsPanel& panel, const char* name) {
  const auto* label = panel.findChild<QLabel*>(QString::fromLatin1(name));
  return label ? label->text() : QStringLiteral("<no label %1>").arg(name);
}

SessionMetrics KnownMetrics() {
  SessionMetrics m;
  m.duration_s = 754.4;
  m.path_length_left_m = 1.2346;
  m.path_length_right_m = 0.875;
  m.slips = 3;
  m.cautery_on_s = 42.6;
  m.liver_damage_m2 = 1.25e-5;
  m.gallbladder_damage_m2 = 3e-6;
  m.max_force_N = 4.567;
  m.mean_force_N = 1.2;
  m.tissue_removed_fraction = 0.4567;
  m.springs_cut = 80;
  m.springs_total = 86;
  m.gallbladder_free = true;
  m.perforation = true;
  m.success = false;
  return m;
}

TEST(MetricsPanelTest, ShowsFormattedValuesWithUnits) {
  MetricsPanel panel;
  panel.Show(KnownMetrics());
  EXPECT_EQ(LabelText(panel, "metric_duration"), "12:34");
  EXPECT_EQ(LabelText(panel, "metric_path_length_left"), "123.5 cm");
  EXPECT_EQ(LabelText(panel, "metric_path_length_right"), "87.5 cm");
  EXPECT_EQ(LabelText(panel, "metric_slips"), "3");
  EXPECT_EQ(LabelText(panel, "metric_cautery_on"), "00:43");
  EXPECT_EQ(LabelText(panel, "metric_liver_damage"), QString::fromUtf8("12.5 mm²"));
  EXPECT_EQ(LabelText(panel, "metric_gallbladder_damage"), QString::fromUtf8("3.0 mm²"));
  EXPECT_EQ(LabelText(panel, "metric_max_force"), "4.57 N");
  EXPECT_EQ(LabelText(panel, "metric_mean_force"), "1.20 N");
  EXPECT_EQ(LabelText(panel, "metric_tissue_removed"), "45.7 %");
  EXPECT_EQ(LabelText(panel, "metric_springs_cut"), "80 / 86");
  EXPECT_EQ(LabelText(panel, "metric_success"), "no (perforated)");
  EXPECT_EQ(panel.ValueText("metric_slips"), "3");
  EXPECT_EQ(panel.ValueText("no_such_label"), "");
}

TEST(MetricsPanelTest, SuccessAndNotFreeReasons) {
  MetricsPanel panel;
  SessionMetrics m = KnownMetrics();
  m.perforation = false;
  m.success = true;
  panel.Show(m);
  EXPECT_EQ(LabelText(panel, "metric_success"), "yes (gallbladder free, no perforation)");
  m.gallbladder_free = false;
  m.success = false;
  panel.Show(m);
  EXPECT_EQ(LabelText(panel, "metric_success"), "no (not free)");
}

TEST(MetricsPanelTest, EveryLabelNamedAndClearRestoresPlaceholders) {
  MetricsPanel panel;
  for (const char* name : kMetricsPanelLabels) EXPECT_EQ(LabelText(panel, name), QString::fromUtf8("–")) << name;
  panel.Show(KnownMetrics());
  panel.Clear();
  for (const char* name : kMetricsPanelLabels) EXPECT_EQ(LabelText(panel, name), QString::fromUtf8("–")) << name;
  for (const char* name : kBiopsyPanelLabels) EXPECT_EQ(LabelText(panel, name), QString::fromUtf8("–")) << name;
  for (const char* name : kCalotPanelLabels) EXPECT_EQ(LabelText(panel, name), QString::fromUtf8("–")) << name;
  EXPECT_EQ(panel.findChildren<QLabel*>(QRegularExpression("^metric_")).size(),
            static_cast<int>(kMetricsPanelLabels.size() + kBiopsyPanelLabels.size() + kCalotPanelLabels.size()));
}

}  // namespace
}  // namespace vesica::app
