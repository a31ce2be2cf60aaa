#pragma once
// How the laparoscope view shades surfaces, chosen at run time (no VTK). Physically based
// (VTK 9's PBR: base colour, roughness, metallic, normal maps) by default; Phong as the fallback
// for OpenGL drivers that draw PBR wrongly or slowly: set VESICA_MATERIALS=phong.

#include <cstdlib>
#include <string_view>

namespace vesica::app {

enum class MaterialModel { kPhysicallyBased, kPhong };

/// VESICA_MATERIALS=phong gives kPhong; anything else, or unset, kPhysicallyBased.
inline MaterialModel MaterialModelFromEnvironment() {
  const char* value = std::getenv("VESICA_MATERIALS");
  return value != nullptr && std::string_view(value) == "phong" ? MaterialModel::kPhong
                                                                : MaterialModel::kPhysicallyBased;
}

/// PBR's Lambert term is albedo / pi and its output is gamma-encoded: its light is brighter than
/// Phong's by about this factor for the same picture at the working distance.
inline constexpr double kPbrLightGain = 2.2;

/// Physically based looks of the tissues (roughness 0 = mirror, 1 = matte).
inline constexpr double kLiverRoughness = 0.22;        // smooth glistening capsule, wet
inline constexpr double kGallbladderRoughness = 0.28;  // thin, wet serosa
inline constexpr double kWallRoughness = 0.5;          // peritoneum seen from inside
inline constexpr double kContextRoughness = 0.38;      // fat, bowel, ducts: wet but lumpy
/// How strongly the normal map tilts the surface (VTK's normal scale).
inline constexpr double kTissueNormalScale = 0.5;

}  // namespace vesica::app
