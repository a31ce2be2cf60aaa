#include "app/history/learning_curve_plot.h"

#include <gtest/gtest.h>

#include <QImage>
#include <QPixmap>

namespace vesica::app {
namespace {

std::vector<SessionMetrics> ThreeSessions() {
  std::vector<SessionMetrics> sessions(3);
  sessions[0].duration_s = 900;
  sessions[1].duration_s = 720;
  sessions[2].duration_s = 480.5;
  sessions[0].slips = 7;
  sessions[1].slips = 4;
  sessions[2].slips = 1;
  sessions[0].liver_damage_m2 = 4e-5;
  sessions[1].liver_damage_m2 = 2.5e-5;
  sessions[2].liver_damage_m2 = 5e-6;
  return sessions;
}

// The curve's blue, as LearningCurvePlot draws it.
bool IsCurveColour(QRgb pixel) {
  return std::abs(qRed(pixel) - 0x1f) <= 8 && std::abs(qGreen(pixel) - 0x6f) <= 8 && std::abs(qBlue(pixel) - 0xb4) <= 8;
}

// Any pixel within one of `at` has the curve's colour (an antialiased 2 px line is fully
// covered only near its centre line).
bool CurveNear(const QImage& image, QPointF at) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const QPoint pixel(static_cast<int>(at.x()) + dx, static_cast<int>(at.y()) + dy);
      if (image.rect().contains(pixel) && IsCurveColour(image.pixel(pixel))) return true;
    }
  return false;
}

int CurvePixels(const QImage& image) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) count += IsCurveColour(image.pixel(x, y));
  return count;
}

TEST(LearningCurvePlotTest, PointsAreTheSessionsInOrder) {
  LearningCurvePlot plot;
  plot.SetSessions(ThreeSessions());
  EXPECT_EQ(plot.Metric().key, std::string_view("duration_s"));
  EXPECT_EQ(plot.Points(), (std::vector<QPointF>{{1, 900}, {2, 720}, {3, 480.5}}));
  EXPECT_EQ(plot.XTicks(), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(plot.YTicks().values, (std::vector<double>{0, 200, 400, 600, 800, 1000}));
}

TEST(LearningCurvePlotTest, ChoosingAMetricReplots) {
  LearningCurvePlot plot;
  plot.SetSessions(ThreeSessions());
  ASSERT_TRUE(plot.SetMetric(std::string_view("slips")));
  EXPECT_EQ(plot.MetricIndex(), FindPlotMetric("slips"));
  EXPECT_EQ(plot.Points(), (std::vector<QPointF>{{1, 7}, {2, 4}, {3, 1}}));
  EXPECT_EQ(plot.YTicks().values, (std::vector<double>{0, 2, 4, 6, 8}));
  ASSERT_TRUE(plot.SetMetric(std::string_view("liver_damage_m2")));  // plotted in mm²
  ASSERT_EQ(plot.Points().size(), 3u);
  EXPECT_DOUBLE_EQ(plot.Points()[0].y(), 40.0);
  EXPECT_DOUBLE_EQ(plot.Points()[1].y(), 25.0);
  EXPECT_DOUBLE_EQ(plot.Points()[2].y(), 5.0);
}

TEST(LearningCurvePlotTest, BadMetricChoiceChangesNothing) {
  LearningCurvePlot plot;
  plot.SetSessions(ThreeSessions());
  ASSERT_TRUE(plot.SetMetric(3));
  EXPECT_FALSE(plot.SetMetric(-1));
  EXPECT_FALSE(plot.SetMetric(static_cast<int>(kPlotMetrics.size())));
  EXPECT_FALSE(plot.SetMetric(std::string_view("success")));
  EXPECT_EQ(plot.MetricIndex(), 3);
}

TEST(LearningCurvePlotTest, DrawsEachPointWhereToPixelSays) {
  LearningCurvePlot plot;
  plot.resize(400, 300);
  plot.SetSessions(ThreeSessions());
  const QImage image = plot.grab().toImage();
  ASSERT_EQ(image.size(), QSize(400, 300));
  for (const QPointF& p : plot.Points()) {
    const QPoint pixel = plot.ToPixel(p).toPoint();
    ASSERT_TRUE(image.rect().contains(pixel));
    EXPECT_TRUE(IsCurveColour(image.pixel(pixel))) << p.x() << ", " << p.y();
  }
  // The first session is left of the last and, with a falling duration, higher on screen.
  EXPECT_LT(plot.ToPixel(plot.Points()[0]).x(), plot.ToPixel(plot.Points()[2]).x());
  EXPECT_LT(plot.ToPixel(plot.Points()[0]).y(), plot.ToPixel(plot.Points()[2]).y());
  // Value 0 sits on the x axis, value 1000 (the top tick) on the top of the data area.
  EXPECT_DOUBLE_EQ(plot.ToPixel({1, 0}).y(), plot.DataArea().bottom());
  EXPECT_DOUBLE_EQ(plot.ToPixel({1, 1000}).y(), plot.DataArea().top());
  // The line between points is drawn too: halfway between sessions 1 and 2.
  const QPointF mid = (plot.ToPixel(plot.Points()[0]) + plot.ToPixel(plot.Points()[1])) / 2;
  EXPECT_TRUE(CurveNear(image, mid));
  EXPECT_FALSE(CurveNear(image, mid - QPointF(0, 20)));
}

TEST(LearningCurvePlotTest, EmptyStateDrawsNoCurve) {
  LearningCurvePlot plot;
  plot.resize(400, 300);
  plot.SetSessions({});
  EXPECT_TRUE(plot.Points().empty());
  EXPECT_EQ(plot.EmptyText(), "No sessions");
  plot.SetEmptyText("No sessions of ana");
  EXPECT_EQ(plot.EmptyText(), "No sessions of ana");
  EXPECT_EQ(CurvePixels(plot.grab().toImage()), 0);
  plot.SetSessions(ThreeSessions());
  EXPECT_GT(CurvePixels(plot.grab().toImage()), 100);
}

TEST(LearningCurvePlotTest, OneSessionIsCentred) {
  LearningCurvePlot plot;
  plot.resize(400, 300);
  plot.SetSessions({ThreeSessions()[1]});
  ASSERT_EQ(plot.Points().size(), 1u);
  EXPECT_DOUBLE_EQ(plot.ToPixel(plot.Points()[0]).x(), plot.DataArea().center().x());
  const QImage image = plot.grab().toImage();
  EXPECT_TRUE(IsCurveColour(image.pixel(plot.ToPixel(plot.Points()[0]).toPoint())));
}

}  // namespace
}  // namespace vesica::app
