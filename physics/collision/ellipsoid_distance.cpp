#include "physics/collision/ellipsoid_distance.h"

#include <algorithm>
#include <cmath>

namespace vesica::physics {

EllipsoidSurfacePoint ClosestPointOnEllipsoid(const Eigen::Vector3d& centre_W, const Eigen::Vector3d& semi_axes_m,
                                              const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d e = semi_axes_m;
  const Eigen::Vector3d e2 = e.cwiseProduct(e);
  const Eigen::Vector3d y_signed = p_W - centre_W;
  // Work in the first octant; a coordinate on a principal plane is nudged off it (by far less
  // than any distance that matters) so the root stays bracketed on the smallest axis's side.
  const double tiny = 1e-12 * e.maxCoeff();
  const Eigen::Vector3d y = y_signed.cwiseAbs().cwiseMax(tiny);
  auto f = [&](double t) {
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
      const double r = e[i] * y[i] / (t + e2[i]);
      sum += r * r;
    }
    return sum - 1.0;
  };
  // f decreases on t > -min e_i^2: f(lo) >= 0 (the smallest axis's term alone is 1 there), f(hi) <= 0.
  int k = 0;
  e.minCoeff(&k);
  double lo = -e2[k] + e[k] * y[k];
  double hi = std::max(lo, e.cwiseProduct(y).norm());
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // the interval is down to adjacent doubles
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  Eigen::Vector3d x;
  for (int i = 0; i < 3; ++i) x[i] = std::copysign(e2[i] * y[i] / (t + e2[i]), y_signed[i]);
  EllipsoidSurfacePoint out;
  out.p_Surface_W = centre_W + x;
  out.normal_W = x.cwiseQuotient(e2).normalized();
  const double distance = (y_signed - x).norm();
  const bool inside = y_signed.cwiseQuotient(e).squaredNorm() < 1.0;
  out.signed_distance_m = inside ? -distance : distance;
  return out;
}

}  // namespace vesica::physics
