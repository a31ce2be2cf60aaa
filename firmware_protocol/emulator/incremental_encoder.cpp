#include "firmware_protocol/emulator/incremental_encoder.h"

#include <cmath>
#include <numbers>

namespace vesica::fp::emulator {

IncrementalEncoder::IncrementalEncoder(const EncoderParameters& p, double motor_angle_rad)
    : p_(p), power_up_angle_rad_(motor_angle_rad), revolution_(Revolution(motor_angle_rad)) {}

double IncrementalEncoder::radians_per_count() const {
  return 2.0 * std::numbers::pi / static_cast<double>(p_.counts_per_rev);
}

std::int64_t IncrementalEncoder::Revolution(double motor_angle_rad) const {
  return static_cast<std::int64_t>(std::floor((motor_angle_rad - p_.index_angle_rad) / (2.0 * std::numbers::pi)));
}

void IncrementalEncoder::Update(double motor_angle_rad) {
  count_ = static_cast<std::int32_t>(std::floor((motor_angle_rad - power_up_angle_rad_) / radians_per_count()));
  const std::int64_t rev = Revolution(motor_angle_rad);
  if (rev != revolution_) {
    // The edge crossed is the one between the two revolutions; latch the count it sits at.
    const std::int64_t edge_rev = rev > revolution_ ? rev : revolution_;
    const double edge_angle = p_.index_angle_rad + 2.0 * std::numbers::pi * static_cast<double>(edge_rev);
    index_count_ = static_cast<std::int32_t>(std::floor((edge_angle - power_up_angle_rad_) / radians_per_count()));
    index_seen_ = true;
    index_edges_ += static_cast<std::uint32_t>(rev > revolution_ ? rev - revolution_ : revolution_ - rev);
    revolution_ = rev;
  }
}

}  // namespace vesica::fp::emulator
