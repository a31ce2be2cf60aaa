#include "app/history/axis_ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesica::app {
namespace {

// The smallest of 1, 2, 5 times a power of ten that is >= rough (rough > 0).
double NiceStep(double rough) {
  const double magnitude = std::pow(10.0, std::floor(std::log10(rough)));
  const double residual = rough / magnitude;
  // 1e-9 of slack so that rough = exactly 2 * magnitude does not round up to 5.
  if (residual <= 1 + 1e-9) return magnitude;
  if (residual <= 2 + 1e-9) return 2 * magnitude;
  if (residual <= 5 + 1e-9) return 5 * magnitude;
  return 10 * magnitude;
}

}  // namespace

AxisTicks NiceTicks(double lo, double hi, int max_ticks) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
  if (hi <= lo) hi = lo + 1;
  max_ticks = std::max(max_ticks, 2);
  AxisTicks ticks;
  ticks.step = NiceStep((hi - lo) / (max_ticks - 1));
  const double first = std::floor(lo / ticks.step + 1e-9);
  const double last = std::ceil(hi / ticks.step - 1e-9);
  for (double k = first; k <= last; ++k) {
    const double value = k * ticks.step;
    ticks.values.push_back(value == 0 ? 0.0 : value);
  }
  ticks.decimals = std::max(0, static_cast<int>(-std::floor(std::log10(ticks.step) + 1e-9)));
  return ticks;
}

std::vector<int> SessionNumberTicks(int count, int max_ticks) {
  std::vector<int> ticks;
  if (count <= 0) return ticks;
  max_ticks = std::max(max_ticks, 2);
  if (count <= max_ticks) {
    for (int n = 1; n <= count; ++n) ticks.push_back(n);
    return ticks;
  }
  const int step = static_cast<int>(std::max(1.0, NiceStep(static_cast<double>(count) / (max_ticks - 1))));
  ticks.push_back(1);
  for (int n = step; n <= count; n += step)
    if (n > 1) ticks.push_back(n);
  return ticks;
}

std::string TickLabel(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string label = text;
  if (label.starts_with('-') && label.find_first_not_of("-0.") == std::string::npos) label.erase(0, 1);
  return label;
}

}  // namespace vesica::app
