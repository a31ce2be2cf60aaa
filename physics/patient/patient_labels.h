#pragma once
// The label values of a biopsy patient's label map (issue 33). Every value here has a row in the
// patient's label table (data/patients/*.labels.toml), which is what the app checks a real label
// map against; physics only needs to know which value is which structure.

#include <cstdint>

namespace vesica::physics::patient_label {

inline constexpr std::uint8_t kAir = 0;
inline constexpr std::uint8_t kSkin = 1;
inline constexpr std::uint8_t kFat = 2;  ///< subcutaneous fat
inline constexpr std::uint8_t kMuscle = 3;
inline constexpr std::uint8_t kSpine = 4;
inline constexpr std::uint8_t kSternum = 5;
inline constexpr std::uint8_t kLung = 6;
inline constexpr std::uint8_t kCostophrenicRecess = 7;
inline constexpr std::uint8_t kDiaphragmMuscle = 8;
inline constexpr std::uint8_t kDiaphragmTendon = 9;
inline constexpr std::uint8_t kLiver = 10;
inline constexpr std::uint8_t kLiverCapsule = 11;  ///< the liver's outer voxel layer
inline constexpr std::uint8_t kTumour = 12;
inline constexpr std::uint8_t kGallbladder = 13;
inline constexpr std::uint8_t kColon = 14;
inline constexpr std::uint8_t kSoftTissue = 15;  ///< the rest of the abdomen and mediastinum

/// Rib n (1-12) of each side, its costal cartilage and the intercostal neurovascular bundle along
/// its lower edge. Right side first: right rib n is 20 + n, left rib n is 40 + n, and so on.
inline constexpr int kMaxRib = 12;
[[nodiscard]] constexpr std::uint8_t Rib(bool left, int n) { return static_cast<std::uint8_t>((left ? 40 : 20) + n); }
[[nodiscard]] constexpr std::uint8_t Cartilage(bool left, int n) {
  return static_cast<std::uint8_t>((left ? 80 : 60) + n);
}
[[nodiscard]] constexpr std::uint8_t Bundle(bool left, int n) {
  return static_cast<std::uint8_t>((left ? 120 : 100) + n);
}
/// Which rib a rib, cartilage or bundle label belongs to: side and number, or number 0 if none.
struct RibOf {
  bool left = false;
  int number = 0;
};
[[nodiscard]] constexpr RibOf RibOfLabel(std::uint8_t label) {
  for (int base : {20, 40, 60, 80, 100, 120})
    if (label > base && label <= base + kMaxRib) return {((base / 20) % 2) == 0, label - base};
  return {};
}

[[nodiscard]] constexpr bool IsLiver(std::uint8_t label) {
  return label == kLiver || label == kLiverCapsule || label == kTumour;
}
[[nodiscard]] constexpr bool IsDiaphragm(std::uint8_t label) {
  return label == kDiaphragmMuscle || label == kDiaphragmTendon;
}

}  // namespace vesica::physics::patient_label
