#include "physics/needle/needle_pose.h"

#include <stdexcept>
#include <string>

namespace vesica::physics {

Eigen::Vector3d ValidatedDirection(const NeedlePose& pose, const char* where) {
  if (!pose.tip_m.allFinite())
    throw std::invalid_argument(std::string(where) + ": the needle's tip position is not finite (NaN or infinity)");
  if (!pose.direction.allFinite())
    throw std::invalid_argument(std::string(where) + ": the needle's direction is not finite (NaN or infinity)");
  const double length = pose.direction.norm();
  if (!(length > 1e-9)) throw std::invalid_argument(std::string(where) + ": the needle's direction has zero length");
  return pose.direction / length;
}

}  // namespace vesica::physics
