#pragma once
// A tube's wall and contents: the section properties a discrete elastic rod needs (docs/calot.md).

namespace vesica::physics::calot {

/// A thin-walled tube (duct or artery) with its contents (bile or blood). SI units.
struct TubeMaterial {
  double youngs_modulus_Pa = 1.0e6;           ///< wall's Young's modulus E, > 0
  double outer_radius_m = 0.0015;             ///< > 0
  double wall_thickness_m = 0.0005;           ///< > 0, <= outer_radius_m (== : a solid rod)
  double wall_density_kg_per_m3 = 1100.0;     ///< > 0 (soft tissue)
  double content_density_kg_per_m3 = 1010.0;  ///< >= 0 (bile ~1010, blood ~1060)
  double mass_damping_per_s = 20.0;           ///< mass-proportional damping: force -alpha m v, >= 0
};

/// Throws std::invalid_argument naming the field when a value is out of its range; `where`
/// prefixes the message (a tube's name, a file and line).
void ValidateTubeMaterial(const TubeMaterial& material, const char* where);

double WallArea_m2(const TubeMaterial& material);             ///< pi (ro^2 - ri^2)
double SecondMomentOfArea_m4(const TubeMaterial& material);   ///< pi/4 (ro^4 - ri^4)
double LinearDensity_kg_per_m(const TubeMaterial& material);  ///< wall plus contents

}  // namespace vesica::physics::calot
