#include "physics/fem/elastic_material.h"

#include <cmath>
#include <sstream>

#include "physics/fem/fem_error.h"

namespace vesica::physics {

double LameLambda(const ElasticMaterial& m) {
  const double nu = m.poisson_ratio;
  return m.youngs_modulus_Pa * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double LameMu(const ElasticMaterial& m) { return m.youngs_modulus_Pa / (2.0 * (1.0 + m.poisson_ratio)); }

void ValidateMaterial(const ElasticMaterial& m, const std::string& body_name) {
  auto fail = [&](const char* field, double value, const char* range) {
    std::ostringstream os;
    os << body_name << ": material " << field << " = " << value << " is out of range (" << range << ")";
    throw FemError(os.str());
  };
  if (!std::isfinite(m.youngs_modulus_Pa) || m.youngs_modulus_Pa <= 0.0)
    fail("youngs_modulus_Pa", m.youngs_modulus_Pa, "E > 0");
  // nu -> 0.5 makes lambda blow up (incompressible locking); nu <= -1 makes mu negative.
  if (!std::isfinite(m.poisson_ratio) || m.poisson_ratio >= 0.5 || m.poisson_ratio <= -1.0)
    fail("poisson_ratio", m.poisson_ratio, "-1 < nu < 0.5");
  if (!std::isfinite(m.density_kg_per_m3) || m.density_kg_per_m3 <= 0.0)
    fail("density_kg_per_m3", m.density_kg_per_m3, "rho > 0");
}

}  // namespace vesica::physics
