#include "app/render/burn_colours.h"

#include <algorithm>
#include <cmath>

#include "app/render/render_colours.h"

namespace vesica::app {

float Unit(float value) { return std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f); }

std::array<std::uint8_t, 3> BurnedColour(const double rgb[3], double shade, float burn) {
  const double b = Unit(burn);
  std::array<std::uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) {
    const double v = (1.0 - b) * shade * rgb[c] + b * kCharRgb[c];
    out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(255.0 * v, 0.0, 255.0)));
  }
  return out;
}

}  // namespace vesica::app
