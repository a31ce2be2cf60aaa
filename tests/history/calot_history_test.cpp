// The Calot's triangle step in the history view (issue 36): its metrics in the session table,
// in the selected session's panel, and on learning curves made only of the sessions that had the
// step; "–" for sessions without it.

#include <gtest/gtest.h>

#include <QTableWidget>

#include "app/history/history_window.h"
#include "app/history/learning_curve_plot.h"
#include "app/history/metric_format.h"
#include "app/history/metrics_panel.h"
#include "app/history/plot_metrics.h"
#include "history_test_support.h"

namespace vesica::app {
namespace {

using testing::AnaSessions;
using testing::KnownStore;
using testing::TempDir;

// A cholecystectomy with the Calot step, from `base` an hour later.
SessionRecord WithCalotStep(SessionRecord r, int hours_later) {
  r.started_unix_s += 3600 * hours_later;
  r.ended_unix_s = r.started_unix_s + 600;
  r.scenario = "calot-triangle";
  SessionMetrics& m = r.metrics;
  m.calot_step = true;
  m.cvs_achieved = true;
  m.cvs_time_s = 65.0;
  m.cvs_before_first_clip = true;
  m.cystic_duct_clips = 3;
  m.cystic_artery_clips = 3;
  m.cystic_duct_clips_correct = true;
  m.cystic_artery_clips_correct = true;
  m.cystic_duct_divided_between_clips = true;
  m.cystic_artery_divided_between_clips = true;
  m.calot_passed = true;
  return r;
}

QString Cell(const HistoryWindow& window, int row, int column) {
  const QTableWidgetItem* item = window.Table()->item(row, column);
  return item ? item->text() : QStringLiteral("<empty>");
}

std::vector<double> PlottedY(const HistoryWindow& window) {
  std::vector<double> y;
  for (const QPointF& p : window.Plot()->Points()) y.push_back(p.y());
  return y;
}

class CalotHistoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SessionRecord passed = WithCalotStep(AnaSessions()[2], 1);
    SessionRecord injured = WithCalotStep(AnaSessions()[2], 2);
    injured.metrics.cvs_before_first_clip = false;  // clipped first, then the view
    injured.metrics.cvs_time_s = 130.0;
    injured.metrics.cystic_duct_clips = 1;
    injured.metrics.cystic_duct_clips_correct = false;
    injured.metrics.cystic_duct_divided_between_clips = false;
    injured.metrics.bleeding_events = 2;
    injured.metrics.bile_leaks = 1;
    injured.metrics.bile_duct_injuries = 1;
    injured.metrics.calot_passed = false;
    injured.metrics.success = false;
    injured.metrics.gallbladder_free = false;
    SessionRecord no_view = WithCalotStep(AnaSessions()[2], 3);
    no_view.metrics.cvs_achieved = false;
    no_view.metrics.cvs_before_first_clip = false;
    no_view.metrics.cvs_time_s = 0;
    no_view.metrics.bleeding_events = 1;
    no_view.metrics.calot_passed = false;
    no_view.metrics.success = false;
    for (const SessionRecord& r : {passed, injured, no_view}) store_->Add(r);
  }

  TempDir dir_;
  std::unique_ptr<SessionStore> store_ = KnownStore(dir_.path());
};

TEST_F(CalotHistoryTest, TableShowsTheCriticalViewBleedsAndInjuriesPerSession) {
  HistoryWindow window(*store_);
  ASSERT_EQ(window.Table()->rowCount(), 6);  // ana's three without the step, then three with it
  EXPECT_EQ(window.Table()->horizontalHeaderItem(11)->text(), "Critical view");
  EXPECT_EQ(window.Table()->horizontalHeaderItem(12)->text(), "Bleeds");
  EXPECT_EQ(window.Table()->horizontalHeaderItem(13)->text(), "Bile duct injuries");
  const QString none = QString::fromUtf8("–");
  const QStringList expected[] = {{none, none, none}, {none, none, none}, {none, none, none},
                                  {"yes", "0", "0"},  {"late", "2", "1"}, {"no", "1", "0"}};
  for (int row = 0; row < 6; ++row)
    for (int column = 0; column < 3; ++column)
      EXPECT_EQ(Cell(window, row, 11 + column), expected[row][column]) << "row " << row << " column " << column;
  EXPECT_EQ(Cell(window, 4, 5), "no");
}

TEST_F(CalotHistoryTest, PanelShowsTheCalotRowsOnlyForSessionsWithTheStep) {
  HistoryWindow window(*store_);
  const MetricsPanel* panel = window.SelectedSession();
  window.Table()->selectRow(4);
  for (const char* name : kCalotPanelLabels) EXPECT_TRUE(panel->RowShown(QString::fromLatin1(name))) << name;
  EXPECT_EQ(panel->ValueText("metric_critical_view"), "yes at 02:10, after the first clip");
  EXPECT_EQ(panel->ValueText("metric_cystic_duct_clips"), "1 (misplaced)");
  EXPECT_EQ(panel->ValueText("metric_cystic_artery_clips"), "3 (placed correctly)");
  EXPECT_EQ(panel->ValueText("metric_division"), "duct not between clips");
  EXPECT_EQ(panel->ValueText("metric_bleeding_events"), "2");
  EXPECT_EQ(panel->ValueText("metric_bile_leaks"), "1");
  EXPECT_EQ(panel->ValueText("metric_bile_duct_injuries"), "1");
  EXPECT_EQ(panel->ValueText("metric_calot_outcome"), "failed (bile duct injury)");
  EXPECT_EQ(panel->ValueText("metric_success"), "no (not free, bile duct injury)");
  window.Table()->selectRow(3);
  EXPECT_EQ(panel->ValueText("metric_critical_view"), "yes at 01:05, before the first clip");
  EXPECT_EQ(panel->ValueText("metric_calot_outcome"), "passed");
  window.Table()->selectRow(0);
  for (const char* name : kCalotPanelLabels) EXPECT_FALSE(panel->RowShown(QString::fromLatin1(name))) << name;
  EXPECT_EQ(panel->ValueText("metric_critical_view"), QString::fromUtf8("–"));
  EXPECT_TRUE(panel->RowShown("metric_slips"));
}

TEST_F(CalotHistoryTest, CalotCurvesHoldOnlyTheSessionsThatMeasureThem) {
  HistoryWindow window(*store_);
  ASSERT_TRUE(window.SelectMetric("bile_duct_injuries"));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{0, 1, 0}));
  ASSERT_TRUE(window.SelectMetric("bleeding_events"));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{0, 2, 1}));
  ASSERT_TRUE(window.SelectMetric("cvs_time_s"));  // the session without the view is no point
  EXPECT_EQ(PlottedY(window), (std::vector<double>{65, 130}));
  ASSERT_TRUE(window.SelectMetric("duration_s"));  // every cholecystectomy, with the step or not
  EXPECT_EQ(PlottedY(window).size(), 6u);
}

TEST(CalotMetricFormatTest, SessionsWithoutTheStepReadNotAssessed) {
  const SessionMetrics none;
  const std::string dash = "–";
  EXPECT_EQ(FormatCriticalView(none), dash);
  EXPECT_EQ(FormatCriticalViewShort(none), dash);
  EXPECT_EQ(FormatDivision(none), dash);
  EXPECT_EQ(FormatCalotOutcome(none), dash);
  EXPECT_EQ(FormatOutcome(none), "no (not free)");  // unchanged without the step
  SessionMetrics m;
  m.calot_step = true;
  m.gallbladder_free = true;
  EXPECT_EQ(FormatCriticalView(m), "no");
  EXPECT_EQ(FormatDivision(m), "neither between clips");
  EXPECT_EQ(FormatCalotOutcome(m), "failed");
  EXPECT_EQ(FormatOutcome(m), "no (Calot step failed)");
  m.cystic_artery_divided_between_clips = true;
  EXPECT_EQ(FormatDivision(m), "duct not between clips");
  m.cystic_duct_divided_between_clips = true;
  EXPECT_EQ(FormatDivision(m), "both between clips");
  EXPECT_EQ(FormatClips(2, false), "2 (misplaced)");
}

TEST(CalotPlotMetricsTest, OnlySessionsWithTheStepAreMeasured) {
  const PlotMetric& injuries = kPlotMetrics[FindPlotMetric("bile_duct_injuries")];
  const PlotMetric& cvs = kPlotMetrics[FindPlotMetric("cvs_time_s")];
  SessionMetrics m;
  EXPECT_FALSE(PlotsSession(injuries, m));
  EXPECT_TRUE(PlotsSession(kPlotMetrics[FindPlotMetric("slips")], m));
  m.calot_step = true;
  EXPECT_TRUE(PlotsSession(injuries, m));
  EXPECT_FALSE(PlotsSession(cvs, m));
  m.cvs_achieved = true;
  EXPECT_TRUE(PlotsSession(cvs, m));
  EXPECT_EQ(AxisTitle(cvs), "Calot: time to the critical view (s)");
}

}  // namespace
}  // namespace vesica::app
