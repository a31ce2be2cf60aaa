#include "physics/fem/time_integrator.h"

namespace vesica::physics {

SystemCoefficients IntegratorCoefficients(const FemSettings& s) {
  const double h = s.time_step_s;
  if (s.integrator == TimeIntegrator::kBackwardEuler) return {1.0 / (h * h), 1.0 / h};
  return {1.0 / (s.newmark_beta * h * h), s.newmark_gamma / (s.newmark_beta * h)};
}

SystemScales SystemMatrixScales(const FemSettings& s) {
  const SystemCoefficients c = IntegratorCoefficients(s);
  return {c.mass + c.damping * s.rayleigh_mass_per_s, 1.0 + c.damping * s.rayleigh_stiffness_s};
}

// Newmark: a+ = a0 du - a2 v - a3 a, v+ = a1 du - a4 v - a5 a with a0 = 1/(beta h^2),
// a1 = gamma/(beta h), a2 = 1/(beta h), a3 = 1/(2 beta) - 1, a4 = gamma/beta - 1,
// a5 = h (gamma/(2 beta) - 1). Substituting into M a+ + D v+ + f_int + K du = f gives the drives.
void IntegratorDrives(const FemSettings& s, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                      Eigen::VectorXd& mass_drive, Eigen::VectorXd& damping_drive) {
  const double h = s.time_step_s;
  if (s.integrator == TimeIntegrator::kBackwardEuler) {
    // M (du/h - v)/h + D du/h + f_int + K du = f
    mass_drive = v / h;
    damping_drive.setZero(v.size());
    return;
  }
  const double beta = s.newmark_beta, gamma = s.newmark_gamma;
  mass_drive = v / (beta * h) + (1.0 / (2.0 * beta) - 1.0) * a;
  damping_drive = (gamma / beta - 1.0) * v + h * (gamma / (2.0 * beta) - 1.0) * a;
}

void IntegratorUpdate(const FemSettings& s, const Eigen::VectorXd& du, const Eigen::VectorXd& v,
                      const Eigen::VectorXd& a, Eigen::VectorXd& v_next, Eigen::VectorXd& a_next) {
  const double h = s.time_step_s;
  if (s.integrator == TimeIntegrator::kBackwardEuler) {
    v_next = du / h;
    a_next = (v_next - v) / h;
    return;
  }
  const double beta = s.newmark_beta, gamma = s.newmark_gamma;
  a_next = du / (beta * h * h) - v / (beta * h) - (1.0 / (2.0 * beta) - 1.0) * a;
  v_next = v + h * ((1.0 - gamma) * a + gamma * a_next);
}

}  // namespace vesica::physics
