#pragma once
// Rotation of a corotational element: the rotation part of the polar decomposition F = R S,
// made robust for flat and inverted elements (det F <= 0) by the SVD sign fix of Irving et al.

#include <Eigen/Core>

namespace vesica::physics {

/// R in SO(3) closest to F. When det F < 0 the singular vector of the smallest singular value is
/// flipped, so R stays a proper rotation and the element is pushed back out of inversion.
Eigen::Matrix3d RotationFromDeformationGradient(const Eigen::Matrix3d& F);

}  // namespace vesica::physics
