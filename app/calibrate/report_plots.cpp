#include "app/calibrate/report_plots.h"

#include <QFont>
#include <QGuiApplication>
#include <QImage>
#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "app/calibrate/acceptance.h"

namespace vesica::app::calibrate {
namespace {

// A caller without a Qt application (the command-line tool) gets an offscreen one for its life.
// Qt's notes about the environment (no XDG_RUNTIME_DIR on a service account) are not the
// technician's business; anything else still goes to stderr.
void QuietQtMessages(QtMsgType type, const QMessageLogContext&, const QString& text) {
  if (type == QtDebugMsg || type == QtInfoMsg || text.startsWith("QStandardPaths:")) return;
  std::fprintf(stderr, "%s\n", text.toLocal8Bit().constData());
}

void EnsureGuiApplication() {
  if (QCoreApplication::instance()) return;
  qInstallMessageHandler(QuietQtMessages);
  qputenv("QT_QPA_PLATFORM", "offscreen");
  static int argc = 1;
  static char name[] = "vesica-calibrate";
  static char* argv[] = {name, nullptr};
  static std::unique_ptr<QGuiApplication> app = std::make_unique<QGuiApplication>(argc, argv);
}

struct Range {
  double lo = 0, hi = 1;
  void Pad() {
    if (hi - lo < 1e-12) {
      lo -= 1;
      hi += 1;
    }
    const double p = 0.08 * (hi - lo);
    lo -= p;
    hi += p;
  }
};

// One panel: axes with ticks, title and labels; to_px maps data to pixels.
struct Panel {
  QRectF box;
  Range x, y;
  QPointF Px(double vx, double vy) const {
    return {box.left() + (vx - x.lo) / (x.hi - x.lo) * box.width(),
            box.bottom() - (vy - y.lo) / (y.hi - y.lo) * box.height()};
  }
  void DrawAxes(QPainter& p, const QString& title, const QString& xlabel, const QString& ylabel) const {
    p.setPen(QPen(QColor(40, 40, 40), 1));
    p.drawRect(box);
    QFont f = p.font();
    f.setPointSize(8);
    p.setFont(f);
    for (int i = 0; i <= 4; ++i) {
      const double vx = x.lo + i * (x.hi - x.lo) / 4, vy = y.lo + i * (y.hi - y.lo) / 4;
      const QPointF px = Px(vx, y.lo), py = Px(x.lo, vy);
      p.setPen(QPen(QColor(225, 225, 225), 1));
      p.drawLine(QPointF(px.x(), box.top()), QPointF(px.x(), box.bottom()));
      p.drawLine(QPointF(box.left(), py.y()), QPointF(box.right(), py.y()));
      p.setPen(QColor(40, 40, 40));
      p.drawText(QRectF(px.x() - 40, box.bottom() + 2, 80, 14), Qt::AlignHCenter, QString::number(vx, 'g', 3));
      p.drawText(QRectF(box.left() - 64, py.y() - 7, 60, 14), Qt::AlignRight, QString::number(vy, 'g', 3));
    }
    f.setPointSize(9);
    f.setBold(true);
    p.setFont(f);
    p.drawText(QRectF(box.left(), box.top() - 22, box.width(), 18), Qt::AlignHCenter, title);
    f.setBold(false);
    f.setPointSize(9);
    p.setFont(f);
    p.drawText(QRectF(box.left(), box.bottom() + 18, box.width(), 16), Qt::AlignHCenter, xlabel);
    p.save();
    p.translate(box.left() - 70, box.center().y());
    p.rotate(-90);
    p.drawText(QRectF(-box.height() / 2, -16, box.height(), 16), Qt::AlignHCenter, ylabel);
    p.restore();
  }
};

bool Save(QImage& image, const std::string& path, std::string* error) {
  if (!image.save(QString::fromStdString(path), "PNG")) {
    *error = "cannot write " + path;
    return false;
  }
  return true;
}

std::vector<int> Joints(unsigned joints) {
  std::vector<int> js;
  for (int j = 0; j < 3; ++j)
    if ((joints >> j) & 1u) js.push_back(j);
  return js;
}

// Panels side by side, one per joint.
QImage Canvas(std::size_t panels, std::vector<QRectF>* boxes) {
  const int w = 380, h = 320;
  QImage image(static_cast<int>(std::max<std::size_t>(panels, 1)) * w, h, QImage::Format_RGB32);
  image.fill(Qt::white);
  for (std::size_t k = 0; k < panels; ++k)
    boxes->push_back(QRectF(static_cast<double>(k) * w + 85, 35, w - 105, h - 90));
  return image;
}

}  // namespace

bool PlotFrictionFit(const device::calibration::CalibrationResult& r, unsigned joints, const std::string& path,
                     std::string* error) {
  EnsureGuiApplication();
  const std::vector<int> js = Joints(joints);
  std::vector<QRectF> boxes;
  QImage image = Canvas(js.size(), &boxes);
  QPainter p(&image);
  p.setRenderHint(QPainter::Antialiasing);
  for (std::size_t k = 0; k < js.size(); ++k) {
    const int j = js[k];
    const auto& c = r.joint[j];
    const auto fit = [&](double v) {
      return c.friction_offset + c.coulomb * (v > 0 ? 1 : v < 0 ? -1 : 0) + c.viscous * v;
    };
    Panel panel{boxes[k], {}, {}};
    double vmax = 1e-9, tmin = 1e30, tmax = -1e30;
    for (const auto& s : c.friction_segments) {
      vmax = std::max(vmax, std::abs(s.velocity));
      tmin = std::min(tmin, s.torque);
      tmax = std::max(tmax, s.torque);
    }
    tmin = std::min(tmin, fit(-vmax));
    tmax = std::max(tmax, fit(vmax));
    panel.x = {-1.1 * vmax, 1.1 * vmax};
    panel.y = {tmin, tmax};
    panel.y.Pad();
    const bool rotary = j < 2;
    panel.DrawAxes(
        p, QString("%1: Coulomb %2, viscous %3").arg(JointName(j)).arg(c.coulomb, 0, 'g', 3).arg(c.viscous, 0, 'g', 3),
        rotary ? "velocity (rad/s)" : "velocity (m/s)", rotary ? "torque (N m)" : "force (N)");
    p.setClipRect(panel.box);
    // The fit: two straight branches with the Coulomb step at zero.
    p.setPen(QPen(QColor(200, 60, 40), 2));
    p.drawLine(panel.Px(-1.1 * vmax, fit(-1.1 * vmax)), panel.Px(-1e-12, fit(-1e-12)));
    p.drawLine(panel.Px(1e-12, fit(1e-12)), panel.Px(1.1 * vmax, fit(1.1 * vmax)));
    p.setPen(QPen(QColor(30, 90, 180), 1.5));
    p.setBrush(QColor(30, 90, 180));
    for (const auto& s : c.friction_segments) p.drawEllipse(panel.Px(s.velocity, s.torque), 3.5, 3.5);
    p.setBrush(Qt::NoBrush);
    p.setClipping(false);
  }
  p.end();
  return Save(image, path, error);
}

bool PlotRangeSweep(const std::vector<PositionSample>& sweep, unsigned joints, const std::string& path,
                    std::string* error) {
  EnsureGuiApplication();
  const std::vector<int> js = Joints(joints);
  std::vector<QRectF> boxes;
  QImage image = Canvas(js.size(), &boxes);
  QPainter p(&image);
  p.setRenderHint(QPainter::Antialiasing);
  const double t0 = sweep.empty() ? 0.0 : sweep.front().t_s;
  const double t1 = sweep.empty() ? 1.0 : sweep.back().t_s;
  for (std::size_t k = 0; k < js.size(); ++k) {
    const int j = js[k];
    double lo = 1e30, hi = -1e30;
    for (const auto& s : sweep) {
      lo = std::min(lo, s.position[j]);
      hi = std::max(hi, s.position[j]);
    }
    if (sweep.empty()) lo = hi = 0.0;
    Panel panel{boxes[k], {0.0, std::max(t1 - t0, 1e-3)}, {lo, hi}};
    panel.y.Pad();
    const bool rotary = j < 2;
    panel.DrawAxes(
        p, QString("%1: %2 %3 between the stops").arg(JointName(j)).arg(hi - lo, 0, 'g', 4).arg(rotary ? "rad" : "m"),
        "time in the step (s)", rotary ? "position (rad)" : "position (m)");
    p.setClipRect(panel.box);
    p.setPen(QPen(QColor(200, 60, 40), 1, Qt::DashLine));
    p.drawLine(panel.Px(0, lo), panel.Px(t1 - t0, lo));
    p.drawLine(panel.Px(0, hi), panel.Px(t1 - t0, hi));
    QPainterPath path_line;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
      const QPointF q = panel.Px(sweep[i].t_s - t0, sweep[i].position[j]);
      if (i == 0)
        path_line.moveTo(q);
      else
        path_line.lineTo(q);
    }
    p.setPen(QPen(QColor(30, 90, 180), 1.5));
    p.drawPath(path_line);
    p.setClipping(false);
  }
  p.end();
  return Save(image, path, error);
}

}  // namespace vesica::app::calibrate
