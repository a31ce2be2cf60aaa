#pragma once
// Rotation of a corotational element: the rotation part of the polar decomposition F = R S,
// made robust for flat and inverted elements (det F <= 0) by the SVD sign fix of Irving et al.

#include <Eigen/Core>

namespace vesica::physics {

/// R in SO(3) closest to F. When det F < 0 the singular vector of the smallest singular value is
/// flipped, so R stays a proper rotation and the element is pushed back out of inversion.
Eigen::Matrix3d RotationFromDeformationGradient(const Eigen::Matrix3d& F);

/// The same rotation by a quaternion iteration warm started from q = (x, y, z, w), which is updated
/// in place: Newton's step on the polar condition (skew(R^T F) = 0), falling back to the torque
/// step of Mueller et al. (2016, "A robust method to extract the rotational part of
/// deformations") far from the solution. Quadratic convergence: 2-3 iterations from the last
/// step's rotation. Use it where det F is well above zero (the SVD handles inversion).
Eigen::Matrix3d RotationByQuaternionIteration(const Eigen::Matrix3d& F, Eigen::Vector4d& q, int max_iterations);

}  // namespace vesica::physics
