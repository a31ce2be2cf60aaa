#include "app/anatomy/gallbladder_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesica::app::anatomy {

namespace {

// Distance to a segment whose radius varies linearly along it (good while the taper is mild).
double RoundConeDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra,
                         double rb) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() - (ra + t * (rb - ra));
}

// Polynomial smooth minimum (Quilez): blends two distances over a width k without a crease.
double SmoothMin(double a, double b, double k) {
  if (k <= 0) return std::min(a, b);
  const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1 - h);
}

}  // namespace

GallbladderCentreline DefaultGallbladderCentreline() {
  GallbladderCentreline c;
  // Fundus (anterior, lowest) to neck (posterior, up towards the hilum), then the duct stub
  // running medially and down towards the common bile duct.
  c.points_m = {{-0.048, 0.040, 0.018},    // fundus
                {-0.045, 0.020, 0.022},    // body
                {-0.040, 0.002, 0.025},    // infundibulum
                {-0.034, -0.010, 0.024},   // neck (Hartmann's pouch)
                {-0.027, -0.016, 0.021},   // start of the cystic duct
                {-0.018, -0.022, 0.017}};  // cut end of the duct stub
  c.radii_m = {0.014, 0.015, 0.010, 0.0065, 0.0035, 0.003};
  c.blend_m = 0.004;
  return c;
}

double GallbladderDistance(const GallbladderCentreline& c, const Eigen::Vector3d& p_W) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < c.points_m.size(); ++i) {
    const double di = RoundConeDistance(p_W, c.points_m[i], c.points_m[i + 1], c.radii_m[i], c.radii_m[i + 1]);
    d = std::isinf(d) ? di : SmoothMin(d, di, c.blend_m);
  }
  return d;
}

Box GallbladderBounds(const GallbladderCentreline& c, double margin_m) {
  Box box{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
          Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (size_t i = 0; i < c.points_m.size(); ++i) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(c.radii_m[i] + margin_m);
    box.min_m = box.min_m.cwiseMin(c.points_m[i] - r);
    box.max_m = box.max_m.cwiseMax(c.points_m[i] + r);
  }
  return box;
}

}  // namespace vesica::app::anatomy
