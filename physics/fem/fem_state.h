#pragma once
// The mutable per-step data of a FEM body (STYLE.md item 2); sizes are 3n, stacked x0 y0 z0 x1 ...

#include <Eigen/Core>

namespace vesica::physics {

struct FemState {
  Eigen::VectorXd displacement_m;         ///< u = x - X
  Eigen::VectorXd velocity_m_per_s;       ///< v
  Eigen::VectorXd acceleration_m_per_s2;  ///< a (used by Newmark)
  Eigen::VectorXd external_force_N;       ///< f_ext applied during the next step
  double time_s = 0.0;
  long long steps = 0;
};

}  // namespace vesica::physics
