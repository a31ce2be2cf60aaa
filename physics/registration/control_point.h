#pragma once
// A control point tracked on a 2D dynamic slice (registration seed section 3.1): a point of the
// organ's outline in the world frame, the inward normal of the outline there and how much the
// tracker trusts it. One set per image frame.

#include <Eigen/Core>
#include <vector>

namespace vesica::physics {

struct ControlPoint {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();              ///< metres, world frame
  Eigen::Vector3d inward_normal_W = Eigen::Vector3d::Zero();  ///< unit, pointing into the organ
  double confidence = 1.0;  ///< (0, 1]: 1 a hard constraint, lower a softer one (eq. 6)
  int plane = 0;            ///< the slice the point was tracked on (coronal, sagittal, ...)
};

/// The control points of one image frame.
struct ControlFrame {
  int frame = 0;
  double time_s = 0.0;
  std::vector<ControlPoint> points;
};

}  // namespace vesica::physics
