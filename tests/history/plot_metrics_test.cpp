#include "app/history/plot_metrics.h"

#include <gtest/gtest.h>

namespace vesica::app {
namespace {

TEST(PlotMetricsTest, EveryKeyIsTheStoredColumnOfItsMember) {
  for (const PlotMetric& metric : kPlotMetrics) {
    int matches = 0;
    for (const MetricField& field : kMetricFields)
      if (std::string_view(field.name) == metric.key) {
        ++matches;
        EXPECT_TRUE(field.member == metric.member) << metric.key;
      }
    EXPECT_EQ(matches, 1) << metric.key;
  }
}

TEST(PlotMetricsTest, ValuesInDisplayUnits) {
  SessionMetrics m;
  m.duration_s = 480.5;
  m.liver_damage_m2 = 2.5e-5;
  m.slips = 4;
  m.tissue_removed_fraction = 0.75;
  m.path_length_left_m = 2.75;
  EXPECT_EQ(PlotValue(kPlotMetrics[FindPlotMetric("duration_s")], m), 480.5);
  EXPECT_DOUBLE_EQ(PlotValue(kPlotMetrics[FindPlotMetric("liver_damage_m2")], m), 25.0);
  EXPECT_EQ(PlotValue(kPlotMetrics[FindPlotMetric("slips")], m), 4.0);
  EXPECT_EQ(PlotValue(kPlotMetrics[FindPlotMetric("tissue_removed_fraction")], m), 75.0);
  EXPECT_EQ(PlotValue(kPlotMetrics[FindPlotMetric("path_length_left_m")], m), 275.0);
}

TEST(PlotMetricsTest, FindAndTitle) {
  EXPECT_EQ(FindPlotMetric("duration_s"), 0);
  EXPECT_EQ(FindPlotMetric("success"), -1);  // booleans are not plotted
  EXPECT_EQ(FindPlotMetric(""), -1);
  EXPECT_EQ(AxisTitle(kPlotMetrics[FindPlotMetric("liver_damage_m2")]), "Liver damage (mm²)");
  EXPECT_EQ(AxisTitle(kPlotMetrics[FindPlotMetric("slips")]), "Slips");
}

}  // namespace
}  // namespace vesica::app
