#include "app/render/burn_colours.h"

#include <algorithm>
#include <cmath>

#include "app/render/render_colours.h"

namespace vesica::app {

float Unit(float value) { return std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f); }

std::array<std::uint8_t, 3> BurnedColour(const double rgb[3], double shade, float burn) {
  const double b = Unit(burn);
  double from[3], to[3], t;
  if (b < kCoagulatedLevel) {
    for (int c = 0; c < 3; ++c) from[c] = shade * rgb[c], to[c] = kCoagulatedRgb[c];
    t = b / kCoagulatedLevel;
  } else if (b < kBrownedLevel) {
    for (int c = 0; c < 3; ++c) from[c] = kCoagulatedRgb[c], to[c] = kBrownedRgb[c];
    t = (b - kCoagulatedLevel) / (kBrownedLevel - kCoagulatedLevel);
  } else {
    for (int c = 0; c < 3; ++c) from[c] = kBrownedRgb[c], to[c] = kCharRgb[c];
    t = (b - kBrownedLevel) / (1.0 - kBrownedLevel);
  }
  std::array<std::uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) {
    const double v = (1.0 - t) * from[c] + t * to[c];
    out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(255.0 * v, 0.0, 255.0)));
  }
  return out;
}

}  // namespace vesica::app
