#include "app/anatomy/liver_shape.h"

#include <algorithm>
#include <cmath>

namespace vesica::app::anatomy {

namespace {

double Lerp(double a, double b, double t) { return a + (b - a) * t; }

// Unit-free slab field: < 0 inside the uncarved wedge.
double WedgeField(const LiverShape& s, const Eigen::Vector3d& p) {
  const double u = (p.x() - s.centre_m.x()) / s.half_width_m;
  const double v = (p.y() - s.centre_m.y()) / s.half_depth_m;
  const double t = std::clamp((u + 1) / 2, 0.0, 1.0);  // 0 at the right lobe, 1 at the left
  const double up = Lerp(s.right_lobe_up_m, s.left_lobe_up_m, t);
  const double down = Lerp(s.right_lobe_down_m, s.left_lobe_down_m, t);
  const double dz = p.z() - s.centre_m.z();
  const double w = dz / (dz > 0 ? up : down);
  const double outline =
      std::pow(std::pow(std::abs(u), s.squareness) + std::pow(std::abs(v), s.squareness), 2.0 / s.squareness);
  return outline + w * w - 1;
}

}  // namespace

double LiverField(const LiverShape& s, const GallbladderCentreline& gallbladder, const Eigen::Vector3d& p_W) {
  // The wedge field's gradient is about 2 / (lobe thickness); scaling by a typical 2 cm half
  // thickness makes it roughly metres, so the smooth maximum below blends over a metric width.
  const double wedge_m = 0.5 * 0.02 * WedgeField(s, p_W);
  const double fossa_m = s.gallbladder_gap_m - GallbladderDistance(gallbladder, p_W);
  // Smooth maximum: inside only where inside the wedge and clear of the gallbladder.
  const double k = s.fossa_blend_m;
  const double h = std::clamp(0.5 - 0.5 * (fossa_m - wedge_m) / k, 0.0, 1.0);
  return fossa_m + (wedge_m - fossa_m) * h + k * h * (1 - h);
}

Box LiverBounds(const LiverShape& s) {
  const double up = std::max(s.right_lobe_up_m, s.left_lobe_up_m);
  const double down = std::max(s.right_lobe_down_m, s.left_lobe_down_m);
  return {s.centre_m - Eigen::Vector3d(s.half_width_m, s.half_depth_m, down),
          s.centre_m + Eigen::Vector3d(s.half_width_m, s.half_depth_m, up)};
}

}  // namespace vesica::app::anatomy
