#include "app/needle_mode/ct_slice_widget.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

namespace vesica::app::needle_mode {
namespace {

constexpr double kNeedleLength_m = 0.15;
constexpr double kPathAhead_m = 0.12;
constexpr double kInPlane_m = 0.003;

}  // namespace

CtSliceWidget::CtSliceWidget(QString title, QWidget* parent) : QWidget(parent), title_(std::move(title)) {
  setMinimumSize(200, 200);
  setAttribute(Qt::WA_OpaquePaintEvent);
}

void CtSliceWidget::Show(const biopsy::SlicePlane& plane, const std::vector<float>& hu,
                         const physics::NeedlePose& needle, const std::optional<Eigen::Vector3d>& tumour_centre_W) {
  plane_ = plane;
  needle_ = needle;
  tumour_ = tumour_centre_W;
  image_ = QImage(plane.columns, plane.rows, QImage::Format_Grayscale8);
  for (int row = 0; row < plane.rows; ++row) {
    uchar* line = image_.scanLine(row);
    for (int column = 0; column < plane.columns; ++column)
      line[column] = biopsy::WindowHu(hu[static_cast<std::size_t>(row) * static_cast<std::size_t>(plane.columns) +
                                         static_cast<std::size_t>(column)]);
  }
  update();
}

void CtSliceWidget::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), Qt::black);
  if (image_.isNull()) return;
  // The image square, centred, as large as fits.
  const int side = std::min(width(), height() - 18);
  const QRectF target((width() - side) / 2.0, 18, side, side);
  painter.drawImage(target, image_);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setClipRect(target);
  const double scale = side / static_cast<double>(plane_.columns);
  const auto to_widget = [&](const Eigen::Vector3d& p_W) {
    const biopsy::SlicePoint s = biopsy::ProjectOntoSlice(plane_, p_W);
    return std::pair{QPointF(target.left() + s.pixel.x() * scale, target.top() + s.pixel.y() * scale), s.off_plane_m};
  };
  const Eigen::Vector3d d = needle_.direction.normalized();
  const Eigen::Vector3d tip = needle_.tip_m, hub = tip - kNeedleLength_m * d, ahead = tip + kPathAhead_m * d;
  // The needle: solid where it lies in the slice (within 3 mm), faint where it passes beyond.
  constexpr int kPieces = 30;
  for (int i = 0; i < kPieces; ++i) {
    const auto [a, off_a] = to_widget(hub + (tip - hub) * (i / double(kPieces)));
    const auto [b, off_b] = to_widget(hub + (tip - hub) * ((i + 1) / double(kPieces)));
    const bool in_plane = std::abs(0.5 * (off_a + off_b)) < kInPlane_m;
    painter.setPen(QPen(in_plane ? QColor(80, 255, 120) : QColor(80, 255, 120, 70), in_plane ? 2.5 : 1.5));
    painter.drawLine(a, b);
  }
  painter.setPen(QPen(QColor(255, 220, 60), 1.5, Qt::DashLine));
  painter.drawLine(to_widget(tip).first, to_widget(ahead).first);
  painter.setBrush(QColor(80, 255, 120));
  painter.setPen(Qt::NoPen);
  painter.drawEllipse(to_widget(tip).first, 3.0, 3.0);
  if (tumour_) {
    const auto [c, off] = to_widget(*tumour_);
    painter.setPen(QPen(std::abs(off) < 0.0075 ? QColor(255, 90, 90) : QColor(255, 90, 90, 90), 1.5));
    painter.setBrush(Qt::NoBrush);
    painter.drawLine(c + QPointF(-6, 0), c + QPointF(6, 0));
    painter.drawLine(c + QPointF(0, -6), c + QPointF(0, 6));
  }
  painter.setClipping(false);
  painter.setPen(Qt::white);
  painter.drawText(QRectF(target.left(), 0, target.width(), 16), Qt::AlignLeft | Qt::AlignVCenter, title_);
}

}  // namespace vesica::app::needle_mode
