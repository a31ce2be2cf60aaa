#pragma once
// CIE L*a*b* (D65) of an 8-bit sRGB pixel and the CIE76 colour difference, for image checks
// that speak of "a visible change" in the units colour science uses (Delta E 2.3 is a just
// noticeable difference; 20 is an obvious change of colour).

#include <algorithm>
#include <cmath>

namespace vesica::app::testing {

struct Lab {
  double L = 0, a = 0, b = 0;
};

inline Lab SrgbToLab(int r8, int g8, int b8) {
  const auto linear = [](int v) {
    const double c = std::clamp(v, 0, 255) / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  const double r = linear(r8), g = linear(g8), b = linear(b8);
  // sRGB -> XYZ (D65), normalised by the D65 white.
  const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
  const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
  const auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
  };
  return {116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

/// CIE76: Euclidean distance in L*a*b*.
inline double DeltaE76(const Lab& p, const Lab& q) {
  return std::sqrt((p.L - q.L) * (p.L - q.L) + (p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b));
}

}  // namespace vesica::app::testing
