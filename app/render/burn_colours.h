#pragma once
// Burn colours: tissue whitens (coagulation), then browns and chars with the burn level. No VTK.

#include <array>
#include <cstdint>

namespace vesica::app {

/// 8-bit colour of `rgb` (0..1) scaled by `shade` and burnt to level `burn` (clamped to [0,1]):
/// piecewise linear from the shaded tissue (0) to kCoagulatedRgb (kCoagulatedLevel), kBrownedRgb
/// (kBrownedLevel) and kCharRgb (1). The burnt colours are not shaded: a burn reads the same
/// wherever the texture's mottling puts it.
std::array<std::uint8_t, 3> BurnedColour(const double rgb[3], double shade, float burn);

/// Clamps to [0,1]; NaN becomes 0 (ValidateRenderFrame rejects NaN before it gets here).
float Unit(float value);

}  // namespace vesica::app
