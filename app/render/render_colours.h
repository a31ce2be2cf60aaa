#pragma once
// Colours the laparoscope view paints with (linear RGB 0..1, before lighting). Tests classify
// pixels by them, so they live apart from VTK.

namespace vesica::app {

/// Liver: dark red-brown capsule. Gallbladder: grey-green with a blue cast (bile through a thin wall).
inline constexpr double kLiverRgb[3] = {0.48, 0.14, 0.10};
inline constexpr double kGallbladderRgb[3] = {0.33, 0.48, 0.35};
/// Cautery's colour ramp (BurnedColour): a fresh burn coagulates to a pale tan-white first, then
/// browns (desiccation) and chars to near-black with dose, as electrosurgery does to tissue.
inline constexpr double kCoagulatedRgb[3] = {0.86, 0.78, 0.68};
inline constexpr double kBrownedRgb[3] = {0.40, 0.24, 0.12};
inline constexpr double kCharRgb[3] = {0.07, 0.045, 0.03};
/// Burn levels at which the ramp reaches each colour (tissue at 0, char at 1).
inline constexpr double kCoagulatedLevel = 0.15;
inline constexpr double kBrownedLevel = 0.5;
/// Connective-tissue membrane: thin, whitish yellow, translucent (kMembraneAlpha at opacity 1).
inline constexpr double kMembraneRgb[3] = {0.92, 0.86, 0.62};
inline constexpr double kMembraneAlpha = 0.6;
/// Cautery smoke: greyish white puffs, alpha-blended.
inline constexpr double kSmokeRgb[3] = {0.86, 0.86, 0.84};
/// Grasper jaws while a grasp has slipped: amber-red warning.
inline constexpr double kSlipRgb[3] = {1.0, 0.35, 0.0};
/// The field's status labels: a grasp that holds (muted green), nothing to report (grey).
inline constexpr double kStatusOkRgb[3] = {0.55, 0.85, 0.55};
inline constexpr double kStatusIdleRgb[3] = {0.70, 0.70, 0.70};
/// Cautery hook tip while cutting: glowing orange-white.
inline constexpr double kCauteryGlowRgb[3] = {1.0, 0.75, 0.35};

}  // namespace vesica::app
