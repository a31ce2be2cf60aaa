#include "device/calibration/gravity_fit.h"

#include <Eigen/Dense>
#include <cmath>

namespace vesica::device::calibration {

GravityFit FitGravity(const std::vector<GravityHold>& holds) {
  GravityFit fit;
  if (holds.size() < 2) return fit;
  const auto n = static_cast<Eigen::Index>(holds.size());
  Eigen::MatrixXd a(n, 2);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const GravityHold& h = holds[static_cast<std::size_t>(i)];
    a(i, 0) = std::sin(h.angle_rad);
    a(i, 1) = std::cos(h.angle_rad);
    b(i) = h.holding();
  }
  const Eigen::Vector2d x = a.colPivHouseholderQr().solve(b);
  fit.sin = x(0);
  fit.cos = x(1);
  fit.rms = std::sqrt((a * x - b).squaredNorm() / static_cast<double>(n));
  fit.ok = std::isfinite(fit.sin) && std::isfinite(fit.cos);
  return fit;
}

}  // namespace vesica::device::calibration
