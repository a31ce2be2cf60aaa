#pragma once

#include <cstdint>

namespace vesica::fp::emulator {

/// A quadrature encoder on a motor shaft with one index pulse per revolution. Counts start at
/// zero wherever the shaft was at power-up, so the joint position is known only up to an offset
/// until the firmware has seen the index; the index sits at an unknown mounting angle.
struct EncoderParameters {
  std::int32_t counts_per_rev = 2048;   ///< after x4 quadrature decoding, > 0
  double index_angle_rad = 0.0;         ///< motor angle of the index edge, mounting dependent
  int direction = 1;                    ///< +1, or -1 for an encoder that counts down as the joint moves up
};

class IncrementalEncoder {
 public:
  /// motor_angle_rad: the shaft angle at power-up (from the joint position and transmission).
  IncrementalEncoder(const EncoderParameters& p, double motor_angle_rad);

  /// Updates counts for the new shaft angle and latches the count at the first index crossing.
  void Update(double motor_angle_rad);

  std::int32_t count() const { return count_; }
  bool index_seen() const { return index_seen_; }
  /// Count latched at the last index edge (valid when index_seen()).
  std::int32_t index_count() const { return index_count_; }
  /// Index edges crossed since power-up, either direction (a board's "index seen" interrupt).
  std::uint32_t index_edges() const { return index_edges_; }
  double radians_per_count() const;

 private:
  std::int64_t Revolution(double motor_angle_rad) const;

  EncoderParameters p_;
  double power_up_angle_rad_;
  std::int64_t revolution_;  ///< index edges passed, signed: floor((angle - index) / 2pi)
  std::int32_t count_ = 0;
  bool index_seen_ = false;
  std::int32_t index_count_ = 0;
  std::uint32_t index_edges_ = 0;
};

}  // namespace vesica::fp::emulator
