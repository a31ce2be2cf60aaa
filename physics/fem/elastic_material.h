#pragma once
// Isotropic linear-elastic material of a FEM body (gallbladder paper Table 1: 2.3 kPa, nu 0.45).

#include <string>

namespace vesica::physics {

struct ElasticMaterial {
  double youngs_modulus_Pa = 2.3e3;     ///< E, Pa; > 0
  double poisson_ratio = 0.45;          ///< nu, dimensionless; -1 < nu < 0.5
  double density_kg_per_m3 = 1000.0;    ///< rho, kg/m^3; > 0
};

/// Lame's first parameter lambda = E nu / ((1 + nu)(1 - 2 nu)), Pa.
double LameLambda(const ElasticMaterial& material);
/// Shear modulus mu = E / (2 (1 + nu)), Pa.
double LameMu(const ElasticMaterial& material);

/// Throws FemError naming `body_name` and the offending field when a value is out of range.
void ValidateMaterial(const ElasticMaterial& material, const std::string& body_name);

}  // namespace vesica::physics
