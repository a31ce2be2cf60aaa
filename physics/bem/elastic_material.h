#pragma once
// Isotropic linear-elastic material of a BEM body (gallbladder paper Table 1).

namespace vesica::physics {

struct ElasticMaterial {
  double youngs_modulus_Pa = 170e3;  ///< E, Pa, > 0 (liver: 170 kPa)
  double poisson_ratio = 0.4;        ///< nu, in (-1, 0.5) (liver: 0.4)

  double shear_modulus_Pa() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
};

/// The paper's human liver: E = 170 kPa, nu = 0.4.
inline ElasticMaterial LiverMaterial() { return {170e3, 0.4}; }

/// Throws BemError naming the field when E <= 0 or nu is outside (-1, 0.5) or not finite.
void ValidateElasticMaterial(const ElasticMaterial& material);

}  // namespace vesica::physics
