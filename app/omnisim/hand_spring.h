#pragma once
// The emulated user's hand on the stylus: the stylus tip (with the hand's mass) is pulled toward
// where the hand means to be by a spring and a damper, and pushed by the device's force. So the
// force the trainer renders moves the stylus as it would move a real hand holding it loosely.

#include <Eigen/Core>

namespace vesica::app {

struct HandSpringParameters {
  double mass_kg = 0.05;             ///< stylus + the hand's effective mass at the tip, > 0
  double stiffness_N_per_m = 300.0;  ///< grip stiffness toward the intended position, > 0
  double damping_ratio = 1.0;        ///< of the mass-spring, >= 0 (1: critically damped)
  double damping_N_s_per_m() const;  ///< 2 zeta sqrt(k m)
};

/// m a = k (target - p) - c v + F, stepped semi-implicitly (velocity first): stable for
/// dt < 2 / sqrt(k/m) (0.026 s with the defaults). At rest p = target + F / k.
class HandSpring {
 public:
  /// std::invalid_argument for a parameter out of range.
  HandSpring(const HandSpringParameters& parameters, const Eigen::Vector3d& p0_m);

  /// Advances dt_s > 0 with the hand aiming at target_m and the device pushing with force_N.
  void Step(double dt_s, const Eigen::Vector3d& target_m, const Eigen::Vector3d& force_N);

  const Eigen::Vector3d& position_m() const { return p_; }
  const Eigen::Vector3d& velocity_m_per_s() const { return v_; }
  const HandSpringParameters& parameters() const { return parameters_; }

 private:
  HandSpringParameters parameters_;
  double damping_;
  Eigen::Vector3d p_;
  Eigen::Vector3d v_ = Eigen::Vector3d::Zero();
};

}  // namespace vesica::app
