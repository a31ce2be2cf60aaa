#include "physics/registration/registration_fem_settings.h"

namespace vesica::physics {

FemSettings DefaultRegistrationFemSettings(const std::string& body_name) {
  FemSettings s;
  s.body_name = body_name;
  s.material.youngs_modulus_Pa = 4e3;  // liver parenchyma, a few kPa
  s.material.poisson_ratio = 0.45;
  s.material.density_kg_per_m3 = 1060.0;
  s.element_model = ElementModel::kCorotational;
  s.integrator = TimeIntegrator::kBackwardEuler;
  s.solver = LinearSolverKind::kRotatedFactorPcg;
  s.time_step_s = 0.05;
  s.pcg_relative_tolerance = 1e-4;  // the constraints correct the free step anyway: 1e-6 gave the same registration (to
                                    // 0.01 mm) in 7 iterations instead of 5
  s.pcg_max_iterations = 20;
  return s;
}

}  // namespace vesica::physics
