#include "device/stylus/stylus_force.h"

#include <cstdio>

namespace vesica::device {

std::optional<std::string> ForceProblem(const Eigen::Vector3d& f_N) {
  if (f_N.allFinite()) return std::nullopt;
  char buf[128];
  std::snprintf(buf, sizeof buf, "stylus force (%g, %g, %g) N is not finite", f_N.x(), f_N.y(), f_N.z());
  return std::string(buf);
}

Eigen::Vector3d SaturateForce(const Eigen::Vector3d& f_N, double max_force_N) {
  const double magnitude = f_N.norm();
  if (magnitude <= max_force_N) return f_N;
  return f_N * (max_force_N / magnitude);
}

}  // namespace vesica::device
