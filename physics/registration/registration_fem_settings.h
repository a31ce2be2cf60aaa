#pragma once
// The FEM body a registration runs on: corotational tets (seed section 3.2), backward Euler, the
// rotated-factor PCG (one CHOLMOD factor of the rest system, turned per node), no gravity. The
// material is a regulariser here: only E's ratio to the soft compliances and the mass's to the
// stiffness shape the result (how much of a correction is rigid motion, how much deformation).

#include <string>

#include "physics/fem/fem_settings.h"

namespace vesica::physics {

/// Liver-like defaults: E 4 kPa, nu 0.45, 1,060 kg/m^3, h 0.05 s, PCG to 1e-4 in <= 20 iterations.
FemSettings DefaultRegistrationFemSettings(const std::string& body_name = "registered organ");

}  // namespace vesica::physics
