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
  const auto add = [&](const char* part) { reason += (reason.empty() ? "" : ", ") + std::string(part); };
  if (!metrics.gallbladder_free) add("not free");
  if (metrics.perforation) add("perforated");
  if (metrics.calot_step && metrics.bile_duct_injuries > 0)
    add("bile duct injury");
  else if (metrics.calot_step && !metrics.calot_passed)
    add("Calot step failed");
  return reason.empty() ? "no" : "no (" + reason + ")";
}

namespace {
const char* const kNotAssessed = "–";  // UTF-8 en dash: a session without the Calot step
}  // namespace

std::string FormatCriticalView(const SessionMetrics& m) {
  if (!m.calot_step) return kNotAssessed;
  if (!m.cvs_achieved) return "no";
  return "yes at " + FormatMinutesSeconds(m.cvs_time_s) +
         (m.cvs_before_first_clip ? ", before the first clip" : ", after the first clip");
}

std::string FormatCriticalViewShort(const SessionMetrics& m) {
  if (!m.calot_step) return kNotAssessed;
  if (!m.cvs_achieved) return "no";
  return m.cvs_before_first_clip ? "yes" : "late";
}

std::string FormatClips(int clips, bool placed_correctly) {
  return std::to_string(clips) + (placed_correctly ? " (placed correctly)" : " (misplaced)");
}

std::string FormatDivision(const SessionMetrics& m) {
  if (!m.calot_step) return kNotAssessed;
  const bool duct = m.cystic_duct_divided_between_clips, artery = m.cystic_artery_divided_between_clips;
  if (duct && artery) return "both between clips";
  if (duct) return "artery not between clips";
  if (artery) return "duct not between clips";
  return "neither between clips";
}

std::string FormatCalotOutcome(const SessionMetrics& m) {
  if (!m.calot_step) return kNotAssessed;
  if (m.calot_passed) return "passed";
  return m.bile_duct_injuries > 0 ? "failed (bile duct injury)" : "failed";
}

}  // namespace vesica::app
