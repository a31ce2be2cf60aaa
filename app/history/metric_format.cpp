#include "app/history/metric_format.h"

#include <cmath>
#include <cstdio>

namespace vesica::app {
namespace {

std::string Fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string result = text;
  // No "-0.0" for tiny negative values.
  if (result.starts_with('-') && result.find_first_not_of("-0.") == std::string::npos) result.erase(0, 1);
  return result;
}

}  // namespace

std::string FormatMinutesSeconds(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long long total = std::llround(seconds);
  char text[32];
  std::snprintf(text, sizeof text, "%02lld:%02lld", total / 60, total % 60);
  return text;
}

std::string FormatCentimetres(double metres) { return Fixed(metres * 100.0, 1); }

std::string FormatSquareMillimetres(double square_metres) { return Fixed(square_metres * 1e6, 1); }

std::string FormatNewtons(double newtons) { return Fixed(newtons, 2); }

std::string FormatPercent(double fraction) { return Fixed(fraction * 100.0, 1); }

std::string FormatMillimetres(double metres) { return Fixed(metres * 1e3, 1); }

std::string FormatSpecimen(double sample_distance_m) {
  if (!std::isfinite(sample_distance_m) || sample_distance_m < 0) return "-";
  if (sample_distance_m < 0.005) return "necrotic debris";
  if (sample_distance_m < 0.010) return "good specimen";
  if (sample_distance_m < 0.015) return "some tumour cells";
  return "not pathologic";
}

std::string FormatBiopsyOutcome(const SessionMetrics& metrics) {
  const std::string verdict = metrics.success ? "yes" : "no";
  if (!metrics.biopsy_sampled) return verdict + " (no sample)";
  return verdict + " (" + FormatSpecimen(metrics.sample_distance_m) + ")";
}

std::string FormatOutcome(const SessionMetrics& metrics) {
  if (metrics.success) return "yes (gallbladder free, no perforation)";
  std::string reason;
  if (!metrics.gallbladder_free) reason = "not free";
  if (metrics.perforation) reason += reason.empty() ? "perforated" : ", perforated";
  return reason.empty() ? "no" : "no (" + reason + ")";
}

}  // namespace vesica::app
