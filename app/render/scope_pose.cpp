#include "app/render/scope_pose.h"

#include <Eigen/Geometry>

namespace vesica::app {

ScopePose ScopePoseOf(const LaparoscopeConfig& scope) {
  ScopePose pose;
  const Eigen::Vector3d line = scope.look_at_m - scope.position_m;
  pose.forward_W = line.normalized();
  pose.eye_W = scope.position_m + scope.insertion_m * pose.forward_W;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY().dot(pose.forward_W) * pose.forward_W;
  if (up.norm() < 1e-3) up = Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(pose.forward_W) * pose.forward_W;
  pose.up_W = up.normalized();
  return pose;
}

}  // namespace vesica::app
