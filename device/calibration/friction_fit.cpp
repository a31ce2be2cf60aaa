#include "device/calibration/friction_fit.h"

#include <Eigen/Dense>
#include <cmath>

namespace vesica::device::calibration {

FrictionFit FitFriction(const std::vector<FrictionSegment>& segments) {
  FrictionFit fit;
  int up = 0, down = 0;
  for (const FrictionSegment& s : segments) (s.velocity > 0 ? up : down) += s.velocity != 0.0;
  // Both directions are needed to tell Coulomb from the offset, two speeds for viscous.
  if (up < 1 || down < 1 || up + down < 3) return fit;
  const auto n = static_cast<Eigen::Index>(segments.size());
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const FrictionSegment& s = segments[static_cast<std::size_t>(i)];
    a(i, 0) = s.velocity > 0 ? 1.0 : (s.velocity < 0 ? -1.0 : 0.0);
    a(i, 1) = s.velocity;
    a(i, 2) = 1.0;
    b(i) = s.torque;
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(b);
  fit.coulomb = x(0);
  fit.viscous = x(1);
  fit.offset = x(2);
  fit.rms = std::sqrt((a * x - b).squaredNorm() / static_cast<double>(n));
  fit.ok = std::isfinite(fit.coulomb) && std::isfinite(fit.viscous);
  return fit;
}

}  // namespace vesica::device::calibration
