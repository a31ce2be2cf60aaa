#include "physics/needle/biopsy_metrics.h"

#include <cmath>
#include <numeric>
#include <stdexcept>

#include "physics/patient/patient_labels.h"

namespace vesica::physics {
namespace label = patient_label;

std::optional<NoGo> NoGoOfLabel(std::uint8_t l) {
  switch (l) {
    case label::kLung:
      return NoGo::kLung;
    case label::kCostophrenicRecess:
      return NoGo::kCostophrenicRecess;
    case label::kColon:
      return NoGo::kColon;
    case label::kGallbladder:
      return NoGo::kGallbladder;
    case label::kSpine:
    case label::kSternum:
      return NoGo::kBone;
    default:
      break;
  }
  const label::RibOf rib = label::RibOfLabel(l);
  if (rib.number == 0) return std::nullopt;
  if (l == label::Rib(rib.left, rib.number)) return NoGo::kBone;
  if (l == label::Bundle(rib.left, rib.number)) return NoGo::kNeurovascularBundle;
  return std::nullopt;  // costal cartilage
}

std::string_view NoGoName(NoGo kind) {
  switch (kind) {
    case NoGo::kLung:
      return "lung";
    case NoGo::kCostophrenicRecess:
      return "costophrenic recess";
    case NoGo::kColon:
      return "colon";
    case NoGo::kGallbladder:
      return "gallbladder";
    case NoGo::kNeurovascularBundle:
      return "neurovascular bundle";
    case NoGo::kBone:
      return "bone";
  }
  return "?";
}

BiopsyPrecision PrecisionOfDistance(double distance_m) {
  if (!(distance_m >= 0.0) || !std::isfinite(distance_m))
    throw std::invalid_argument("biopsy precision: the distance must be finite and >= 0");
  if (distance_m < 0.005) return BiopsyPrecision::kNecroticDebris;
  if (distance_m < 0.010) return BiopsyPrecision::kGoodSpecimen;
  if (distance_m <= 0.015) return BiopsyPrecision::kSomeTumourCells;
  return BiopsyPrecision::kNotPathologic;
}

std::string_view PrecisionName(BiopsyPrecision precision) {
  switch (precision) {
    case BiopsyPrecision::kNecroticDebris:
      return "necrotic debris";
    case BiopsyPrecision::kGoodSpecimen:
      return "good specimen";
    case BiopsyPrecision::kSomeTumourCells:
      return "some tumour cells";
    case BiopsyPrecision::kNotPathologic:
      return "not pathologic";
  }
  return "?";
}

int BiopsyMetrics::total_no_go_crossings() const {
  return std::accumulate(no_go_crossings.begin(), no_go_crossings.end(), 0);
}

std::optional<double> BiopsyMetrics::time_to_sample_s() const {
  if (!sample) return std::nullopt;
  return sample->time_s - start_s;
}

}  // namespace vesica::physics
