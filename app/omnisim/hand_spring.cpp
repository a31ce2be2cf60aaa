#include "app/omnisim/hand_spring.h"

#include <cmath>
#include <stdexcept>

namespace vesica::app {

double HandSpringParameters::damping_N_s_per_m() const {
  return 2.0 * damping_ratio * std::sqrt(stiffness_N_per_m * mass_kg);
}

HandSpring::HandSpring(const HandSpringParameters& parameters, const Eigen::Vector3d& p0_m)
    : parameters_(parameters), damping_(parameters.damping_N_s_per_m()), p_(p0_m) {
  if (!(parameters.mass_kg > 0) || !std::isfinite(parameters.mass_kg))
    throw std::invalid_argument("hand spring: mass_kg must be > 0 and finite");
  if (!(parameters.stiffness_N_per_m > 0) || !std::isfinite(parameters.stiffness_N_per_m))
    throw std::invalid_argument("hand spring: stiffness_N_per_m must be > 0 and finite");
  if (!(parameters.damping_ratio >= 0) || !std::isfinite(parameters.damping_ratio))
    throw std::invalid_argument("hand spring: damping_ratio must be >= 0 and finite");
  if (!p0_m.allFinite()) throw std::invalid_argument("hand spring: initial position is not finite");
}

void HandSpring::Step(double dt_s, const Eigen::Vector3d& target_m, const Eigen::Vector3d& force_N) {
  const Eigen::Vector3d a =
      (parameters_.stiffness_N_per_m * (target_m - p_) - damping_ * v_ + force_N) / parameters_.mass_kg;
  v_ += dt_s * a;
  p_ += dt_s * v_;
}

}  // namespace vesica::app
