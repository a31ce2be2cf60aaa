#pragma once
// The needle as the stylus gives it (seed 5.1): the position P of its tip and the direction D it
// points (into the patient when inserting), in the world frame (x left, y anterior, z cranial).

#include <Eigen/Core>

namespace vesica::physics {

struct NeedlePose {
  Eigen::Vector3d tip_m = Eigen::Vector3d::Zero();       ///< P: the tip, world, m
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< D: any non-zero length; used normalised
};

/// Throws std::invalid_argument naming the field: a non-finite tip or direction, or a direction
/// shorter than 1e-9 (no direction). Returns D normalised.
Eigen::Vector3d ValidatedDirection(const NeedlePose& pose, const char* where);

}  // namespace vesica::physics
