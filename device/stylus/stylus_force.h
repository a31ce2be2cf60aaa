#pragma once
// The one place a requested stylus force becomes what the device may render.

#include <Eigen/Core>
#include <optional>
#include <string>

namespace vesica::device {

/// What is wrong with a requested force (a non-finite component), or nullopt.
std::optional<std::string> ForceProblem(const Eigen::Vector3d& f_N);

/// f_N scaled down to magnitude max_force_N when it is longer, direction kept. max_force_N >= 0.
Eigen::Vector3d SaturateForce(const Eigen::Vector3d& f_N, double max_force_N);

}  // namespace vesica::device
