#pragma once
// One CT guidance image (issue 34): the slice's pixels through the abdominal window, the needle
// drawn on it (solid where it lies within 3 mm of the plane, faint beyond), its projected path
// ahead of the tip (dashed), and the tumour's centre when it is shown. Qt only; the pixels come
// from biopsy::SampleSlice.

#include <QImage>
#include <QString>
#include <QWidget>
#include <optional>

#include "app/biopsy/ct_slice.h"

namespace vesica::app::needle_mode {

class CtSliceWidget : public QWidget {
 public:
  explicit CtSliceWidget(QString title, QWidget* parent = nullptr);

  /// New pixels (rows x columns HU, SampleSlice) for `plane`, the needle, and the tumour's
  /// centre (nullopt: not drawn).
  void Show(const biopsy::SlicePlane& plane, const std::vector<float>& hu, const physics::NeedlePose& needle,
            const std::optional<Eigen::Vector3d>& tumour_centre_W);

  [[nodiscard]] const QImage& image() const { return image_; }
  [[nodiscard]] const QString& title() const { return title_; }
  QSize sizeHint() const override { return {320, 320}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  QString title_;
  QImage image_;
  biopsy::SlicePlane plane_;
  physics::NeedlePose needle_;
  std::optional<Eigen::Vector3d> tumour_;
};

}  // namespace vesica::app::needle_mode
