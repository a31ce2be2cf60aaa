#include "physics/bem/bem_material.h"

#include <cmath>
#include <string>

#include "physics/bem/bem_errors.h"

namespace vesica::physics {

void ValidateBemMaterial(const ElasticMaterial& material) {
  if (!std::isfinite(material.youngs_modulus_Pa) || material.youngs_modulus_Pa <= 0.0)
    throw BemError("BEM material: youngs_modulus_Pa must be finite and > 0, got " +
                   std::to_string(material.youngs_modulus_Pa));
  if (!std::isfinite(material.poisson_ratio) || material.poisson_ratio <= -1.0 ||
      material.poisson_ratio >= 0.5)
    throw BemError("BEM material: poisson_ratio must lie in (-1, 0.5), got " +
                   std::to_string(material.poisson_ratio));
}

}  // namespace vesica::physics
