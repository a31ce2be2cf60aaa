#pragma once
// The BEM body uses the project's one isotropic material (physics/fem/elastic_material.h); the
// BEM needs only E and nu (statics, no density).

#include "physics/fem/elastic_material.h"

namespace vesica::physics {

/// The paper's human liver (Table 1): E = 170 kPa, nu = 0.4; density 1060 kg/m^3 (unused here).
inline ElasticMaterial LiverMaterial() { return {170e3, 0.4, 1060.0}; }

/// Throws BemError naming the field when E <= 0 or nu is outside (-1, 0.5) or not finite.
void ValidateBemMaterial(const ElasticMaterial& material);

}  // namespace vesica::physics
