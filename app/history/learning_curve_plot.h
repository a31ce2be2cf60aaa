#pragma once
// A trainee's learning curve: one metric of each session in order, x = session number (1 for
// the oldest), y = the metric in its display unit (plot_metrics.h), points joined by lines, with
// ticked and labelled axes. Drawn with QPainter; shows an empty-state text when there are no
// sessions.

#include <QPointF>
#include <QRectF>
#include <QString>
#include <QWidget>
#include <vector>

#include "app/history/axis_ticks.h"
#include "app/history/plot_metrics.h"
#include "app/records/session_metrics.h"

namespace vesica::app {

class LearningCurvePlot : public QWidget {
 public:
  explicit LearningCurvePlot(QWidget* parent = nullptr);

  /// The sessions to plot, oldest first (SessionStore::List order). Empty shows EmptyText().
  void SetSessions(std::vector<SessionMetrics> sessions);

  /// Chooses the plotted metric by kPlotMetrics index; false (and no change) when out of range.
  bool SetMetric(int index);
  /// Chooses the plotted metric by key ("max_force_N"); false (and no change) for an unknown key.
  bool SetMetric(std::string_view key);
  int MetricIndex() const { return metric_index_; }
  const PlotMetric& Metric() const { return kPlotMetrics[metric_index_]; }

  /// The plotted points: (session number, value in the metric's display unit), in session order.
  const std::vector<QPointF>& Points() const { return points_; }

  /// The y-axis ticks for the current points (covering them and 0).
  const AxisTicks& YTicks() const { return y_ticks_; }
  /// The x-axis ticks (session numbers).
  const std::vector<int>& XTicks() const { return x_ticks_; }

  /// The text shown when there is nothing to plot ("No sessions").
  void SetEmptyText(const QString& text);
  const QString& EmptyText() const { return empty_text_; }

  /// Where a data point (session number, display value) lands in widget pixels at the current
  /// size; the area inside the axes is DataArea().
  QPointF ToPixel(const QPointF& point) const;
  QRectF DataArea() const;

  QSize sizeHint() const override { return {480, 300}; }
  QSize minimumSizeHint() const override { return {240, 160}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  void Recompute();

  std::vector<SessionMetrics> sessions_;
  int metric_index_ = 0;
  std::vector<QPointF> points_;
  AxisTicks y_ticks_;
  std::vector<int> x_ticks_;
  QString empty_text_;
};

}  // namespace vesica::app
