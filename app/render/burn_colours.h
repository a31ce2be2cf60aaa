#pragma once
// Burn darkening: tissue colour mixed toward char by burn level. No VTK.

#include <array>
#include <cstdint>

namespace vesica::app {

/// 8-bit colour of `rgb` (0..1) scaled by `shade` and charred by `burn` (clamped to [0,1]):
/// (1 - burn) * shade * rgb + burn * kCharRgb.
std::array<std::uint8_t, 3> BurnedColour(const double rgb[3], double shade, float burn);

/// Clamps to [0,1]; NaN becomes 0 (ValidateRenderFrame rejects NaN before it gets here).
float Unit(float value);

}  // namespace vesica::app
