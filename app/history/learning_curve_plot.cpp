#include "app/history/learning_curve_plot.h"

#include <QFontMetrics>
#include <QPainter>
#include <QPainterPath>
#include <algorithm>

namespace vesica::app {
namespace {

constexpr int kMaxYTicks = 6;
constexpr int kMaxXTicks = 10;
// Pixels between the widget's edge and the data area (room for tick labels and titles).
constexpr double kMarginLeft = 64, kMarginRight = 16, kMarginTop = 16, kMarginBottom = 44;
constexpr double kTickLength = 5;
constexpr double kPointRadius = 3.5;

const QColor kLineColor(0x1f, 0x6f, 0xb4);
const QColor kGridColor(0xe0, 0xe0, 0xe0);

}  // namespace

LearningCurvePlot::LearningCurvePlot(QWidget* parent) : QWidget(parent), empty_text_(QStringLiteral("No sessions")) {
  setBackgroundRole(QPalette::Base);
  setAutoFillBackground(true);
  Recompute();
}

void LearningCurvePlot::SetSessions(std::vector<SessionMetrics> sessions) {
  sessions_ = std::move(sessions);
  Recompute();
}

bool LearningCurvePlot::SetMetric(int index) {
  if (index < 0 || index >= static_cast<int>(kPlotMetrics.size())) return false;
  metric_index_ = index;
  Recompute();
  return true;
}

bool LearningCurvePlot::SetMetric(std::string_view key) { return SetMetric(FindPlotMetric(key)); }

void LearningCurvePlot::SetEmptyText(const QString& text) {
  empty_text_ = text;
  update();
}

void LearningCurvePlot::Recompute() {
  points_.clear();
  for (std::size_t i = 0; i < sessions_.size(); ++i)
    points_.emplace_back(static_cast<double>(i + 1), PlotValue(Metric(), sessions_[i]));
  // The y axis always shows 0, so a learning curve's improvement is not exaggerated.
  double lo = 0, hi = 0;
  for (const QPointF& p : points_) lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
  y_ticks_ = NiceTicks(lo, hi, kMaxYTicks);
  x_ticks_ = SessionNumberTicks(static_cast<int>(points_.size()), kMaxXTicks);
  update();
}

QRectF LearningCurvePlot::DataArea() const {
  return QRectF(QPointF(kMarginLeft, kMarginTop), QPointF(width() - kMarginRight, height() - kMarginBottom));
}

QPointF LearningCurvePlot::ToPixel(const QPointF& point) const {
  const QRectF area = DataArea();
  // Half a session of room either side, so the first and last points are off the axes.
  const double x_lo = 0.5, x_hi = std::max<double>(1, points_.size()) + 0.5;
  const double y_lo = y_ticks_.values.front(), y_hi = y_ticks_.values.back();
  return {area.left() + (point.x() - x_lo) / (x_hi - x_lo) * area.width(),
          area.bottom() - (point.y() - y_lo) / (y_hi - y_lo) * area.height()};
}

void LearningCurvePlot::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  const QColor text_color = palette().color(QPalette::Text);
  if (points_.empty()) {
    painter.setPen(palette().color(QPalette::Disabled, QPalette::Text));
    painter.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap, empty_text_);
    return;
  }
  const QRectF area = DataArea();
  if (area.width() <= 0 || area.height() <= 0) return;
  const QFontMetrics metrics(font());

  // Horizontal grid lines and y ticks with labels.
  for (double y : y_ticks_.values) {
    const double py = ToPixel({0, y}).y();
    painter.setPen(QPen(kGridColor, 1));
    painter.drawLine(QPointF(area.left(), py), QPointF(area.right(), py));
    painter.setPen(QPen(text_color, 1));
    painter.drawLine(QPointF(area.left() - kTickLength, py), QPointF(area.left(), py));
    const QString label = QString::fromStdString(TickLabel(y, y_ticks_.decimals));
    const QRectF box(0, py - metrics.height(), area.left() - kTickLength - 3, 2 * metrics.height());
    painter.drawText(box, Qt::AlignRight | Qt::AlignVCenter, label);
  }
  // X ticks with session numbers.
  for (int n : x_ticks_) {
    const double px = ToPixel({static_cast<double>(n), 0}).x();
    painter.drawLine(QPointF(px, area.bottom()), QPointF(px, area.bottom() + kTickLength));
    const QRectF box(px - 40, area.bottom() + kTickLength + 1, 80, metrics.height());
    painter.drawText(box, Qt::AlignHCenter | Qt::AlignTop, QString::number(n));
  }
  // Axes.
  painter.drawLine(area.bottomLeft(), area.bottomRight());
  painter.drawLine(area.bottomLeft(), area.topLeft());
  // Axis titles: "Session" under the x axis, the metric and unit up the y axis.
  painter.drawText(QRectF(area.left(), height() - metrics.height() - 2, area.width(), metrics.height()),
                   Qt::AlignHCenter, QStringLiteral("Session"));
  painter.save();
  painter.translate(2, area.center().y());
  painter.rotate(-90);
  painter.drawText(QRectF(-area.height() / 2, 0, area.height(), metrics.height()), Qt::AlignHCenter,
                   QString::fromStdString(AxisTitle(Metric())));
  painter.restore();

  // The curve: points joined by lines, then the points on top.
  painter.setClipRect(rect());
  QPainterPath path;
  path.moveTo(ToPixel(points_.front()));
  for (std::size_t i = 1; i < points_.size(); ++i) path.lineTo(ToPixel(points_[i]));
  painter.setPen(QPen(kLineColor, 2));
  painter.setBrush(Qt::NoBrush);
  painter.drawPath(path);
  painter.setPen(Qt::NoPen);
  painter.setBrush(kLineColor);
  for (const QPointF& p : points_) painter.drawEllipse(ToPixel(p), kPointRadius, kPointRadius);
}

}  // namespace vesica::app
