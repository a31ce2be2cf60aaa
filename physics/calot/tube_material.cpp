#include "physics/calot/tube_material.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vesica::physics::calot {
namespace {

void Require(bool ok, const char* where, const char* field, const char* range, double value) {
  if (!ok)
    throw std::invalid_argument(std::string(where) + ": tube material " + field + " must be " + range + ", got " +
                                std::to_string(value));
}

double InnerRadius_m(const TubeMaterial& m) { return m.outer_radius_m - m.wall_thickness_m; }

}  // namespace

void ValidateTubeMaterial(const TubeMaterial& m, const char* where) {
  Require(std::isfinite(m.youngs_modulus_Pa) && m.youngs_modulus_Pa > 0, where, "youngs_modulus_Pa", "> 0",
          m.youngs_modulus_Pa);
  Require(std::isfinite(m.outer_radius_m) && m.outer_radius_m > 0, where, "outer_radius_m", "> 0", m.outer_radius_m);
  Require(m.wall_thickness_m > 0 && m.wall_thickness_m <= m.outer_radius_m, where, "wall_thickness_m",
          "> 0 and <= outer_radius_m", m.wall_thickness_m);
  Require(m.wall_density_kg_per_m3 > 0, where, "wall_density_kg_per_m3", "> 0", m.wall_density_kg_per_m3);
  Require(m.content_density_kg_per_m3 >= 0, where, "content_density_kg_per_m3", ">= 0", m.content_density_kg_per_m3);
  Require(m.mass_damping_per_s >= 0, where, "mass_damping_per_s", ">= 0", m.mass_damping_per_s);
}

double WallArea_m2(const TubeMaterial& m) {
  const double ro = m.outer_radius_m, ri = InnerRadius_m(m);
  return std::numbers::pi * (ro * ro - ri * ri);
}

double SecondMomentOfArea_m4(const TubeMaterial& m) {
  const double ro = m.outer_radius_m, ri = InnerRadius_m(m);
  return std::numbers::pi / 4.0 * (ro * ro * ro * ro - ri * ri * ri * ri);
}

double LinearDensity_kg_per_m(const TubeMaterial& m) {
  const double ri = InnerRadius_m(m);
  return m.wall_density_kg_per_m3 * WallArea_m2(m) + m.content_density_kg_per_m3 * std::numbers::pi * ri * ri;
}

}  // namespace vesica::physics::calot
