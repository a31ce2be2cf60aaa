#pragma once
// Implicit integrators in displacement-increment form. Each step solves
//   S du = f_ext - f_int(u) + M m_drive + D d_drive,   S = c_M M + c_D D + K_t,
// then updates v and a from du. Backward Euler: c_M = 1/h^2, c_D = 1/h (S = C^-1 of the issue);
// Newmark-beta (gallbladder paper eq. 7, K~ = S): c_M = 1/(beta h^2), c_D = gamma/(beta h).
// For a linear body both are exact (no linearisation error).

#include <Eigen/Core>

#include "physics/fem/fem_settings.h"

namespace vesica::physics {

struct SystemCoefficients {
  double mass = 0.0;     ///< c_M, 1/s^2
  double damping = 0.0;  ///< c_D, 1/s
};

SystemCoefficients IntegratorCoefficients(const FemSettings& settings);

/// S = stiffness K_t + mass M (+ springs) with Rayleigh damping D = alpha M + beta K_t folded in:
/// stiffness = 1 + c_D beta (>= 1), mass = c_M + c_D alpha.
struct SystemScales {
  double mass = 0.0;
  double stiffness = 1.0;
};

SystemScales SystemMatrixScales(const FemSettings& settings);

/// The vectors multiplied by M and D on the right-hand side (m_drive, d_drive), from v and a.
void IntegratorDrives(const FemSettings& settings, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                      Eigen::VectorXd& mass_drive, Eigen::VectorXd& damping_drive);

/// New velocity and acceleration from the solved increment du.
void IntegratorUpdate(const FemSettings& settings, const Eigen::VectorXd& du, const Eigen::VectorXd& v,
                      const Eigen::VectorXd& a, Eigen::VectorXd& v_next, Eigen::VectorXd& a_next);

}  // namespace vesica::physics
