#include "physics/fem/fem_settings.h"

#include <cmath>
#include <sstream>

#include "physics/fem/fem_error.h"

namespace vesica::physics {

void ValidateSettings(const FemSettings& s) {
  ValidateMaterial(s.material, s.body_name);
  auto check = [&](bool ok, const char* field, double value, const char* range) {
    if (ok) return;
    std::ostringstream os;
    os << s.body_name << ": setting " << field << " = " << value << " is out of range (" << range << ")";
    throw FemError(os.str());
  };
  check(std::isfinite(s.time_step_s) && s.time_step_s > 0.0, "time_step_s", s.time_step_s, "h > 0");
  check(std::isfinite(s.rayleigh_mass_per_s) && s.rayleigh_mass_per_s >= 0.0, "rayleigh_mass_per_s",
        s.rayleigh_mass_per_s, ">= 0");
  check(std::isfinite(s.rayleigh_stiffness_s) && s.rayleigh_stiffness_s >= 0.0, "rayleigh_stiffness_s",
        s.rayleigh_stiffness_s, ">= 0");
  check(s.newmark_beta > 0.0 && s.newmark_beta <= 0.5, "newmark_beta", s.newmark_beta, "0 < beta <= 0.5");
  check(s.newmark_gamma >= 0.5 && s.newmark_gamma <= 1.0, "newmark_gamma", s.newmark_gamma, "0.5 <= gamma <= 1");
  // 2 beta < gamma is stable only for omega h below a bound, and a tet mesh's stiffest modes are
  // far beyond any usable h: every step would diverge and be rejected.
  if (s.integrator == TimeIntegrator::kNewmark && 2.0 * s.newmark_beta < s.newmark_gamma) {
    std::ostringstream range;
    range << "2 beta >= gamma = " << s.newmark_gamma << ": otherwise only conditionally stable";
    check(false, "newmark_beta", s.newmark_beta, range.str().c_str());
  }
  check(s.pcg_relative_tolerance > 0.0 && s.pcg_relative_tolerance < 1.0, "pcg_relative_tolerance",
        s.pcg_relative_tolerance, "0 < tol < 1");
  check(s.pcg_max_iterations >= 1, "pcg_max_iterations", s.pcg_max_iterations, ">= 1");
  check(s.cholmod_refresh_steps >= 1, "cholmod_refresh_steps", s.cholmod_refresh_steps, ">= 1");
  check(s.rotated_factor_sweeps >= 1, "rotated_factor_sweeps", s.rotated_factor_sweeps, ">= 1");
  check(s.rotated_factor_local_share >= 0.0 && s.rotated_factor_local_share <= 1.0, "rotated_factor_local_share",
        s.rotated_factor_local_share, "0 <= share <= 1");
  check(s.rotated_factor_rotation_refresh_rad >= 0.0 && std::isfinite(s.rotated_factor_rotation_refresh_rad),
        "rotated_factor_rotation_refresh_rad", s.rotated_factor_rotation_refresh_rad, "finite, >= 0");
  check(s.rotated_factor_local_nodes_max >= 0, "rotated_factor_local_nodes_max", s.rotated_factor_local_nodes_max,
        ">= 0");
  check(s.rotated_factor_adopt_steps >= 0, "rotated_factor_adopt_steps", s.rotated_factor_adopt_steps, ">= 0");
  check(s.max_energy_growth >= 1.0, "max_energy_growth", s.max_energy_growth, ">= 1");
  check(s.energy_floor_J >= 0.0, "energy_floor_J", s.energy_floor_J, ">= 0");
}

bool ProductsAreMatrixFree(const FemSettings& s) {
  return s.element_model == ElementModel::kCorotational && s.solver == LinearSolverKind::kRotatedFactorPcg &&
         s.rotated_factor_matrix_free;
}

bool TangentIsMatrixFree(const FemSettings& s) { return ProductsAreMatrixFree(s) && !s.rotated_factor_gauss_seidel; }

}  // namespace vesica::physics
