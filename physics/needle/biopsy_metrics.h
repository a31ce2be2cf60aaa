#pragma once
// The trainee's biopsy metrics (seed 6.3): time from the start to the sample, crossings of 'no go'
// voxels, insertion attempts, and the sample's precision by its distance from the tumour's centre.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace vesica::physics {

/// The seed's 'no go' structures. Bone is rib, spine and sternum (costal cartilage is not bone
/// and a needle passes it in practice, so it is not counted).
enum class NoGo : std::uint8_t { kLung, kCostophrenicRecess, kColon, kGallbladder, kNeurovascularBundle, kBone };
inline constexpr int kNoGoKinds = 6;
[[nodiscard]] std::optional<NoGo> NoGoOfLabel(std::uint8_t patient_label);
[[nodiscard]] std::string_view NoGoName(NoGo kind);

/// Seed 6.3's bands by distance from the tumour's centre: < 5 mm, 5-10, 10-15, > 15 mm.
enum class BiopsyPrecision : std::uint8_t { kNecroticDebris, kGoodSpecimen, kSomeTumourCells, kNotPathologic };
/// Throws std::invalid_argument for a negative or non-finite distance.
[[nodiscard]] BiopsyPrecision PrecisionOfDistance(double distance_m);
[[nodiscard]] std::string_view PrecisionName(BiopsyPrecision precision);

struct BiopsySample {
  double time_s = 0.0;                                        ///< when it was taken
  Eigen::Vector3d site_m = Eigen::Vector3d::Zero();           ///< the needle's tip, world
  Eigen::Vector3d tumour_centre_m = Eigen::Vector3d::Zero();  ///< where the tumour's centre was then
  double distance_m = 0.0;
  BiopsyPrecision precision = BiopsyPrecision::kNotPathologic;
  bool inside_body = false;  ///< a sample taken outside the body is recorded, and is not pathologic
};

struct BiopsyMetrics {
  double start_s = 0.0;
  int insertion_attempts = 0;                     ///< each entry into the skin (after a withdrawal)
  std::array<int, kNoGoKinds> no_go_crossings{};  ///< entries of the tip into each kind, by NoGo
  std::optional<BiopsySample> sample;             ///< the first sample taken ends the task
  [[nodiscard]] int total_no_go_crossings() const;
  [[nodiscard]] int crossings(NoGo kind) const { return no_go_crossings[static_cast<std::size_t>(kind)]; }
  /// Time from the start to the sample, when taken.
  [[nodiscard]] std::optional<double> time_to_sample_s() const;
};

}  // namespace vesica::physics
