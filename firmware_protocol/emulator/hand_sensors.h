#pragma once

#include <cmath>
#include <cstdint>

namespace vesica::fp::emulator {

/// The jaw handle's and the pedal's sensors as their converters read them: 12-bit ADC counts,
/// linear in the jaw's opening and the pedal's travel. Where each sensor sits is an assembly
/// matter, different on every arm: what the guided hand calibration finds (RandomArm draws it).
struct HandSensorModel {
  double jaw_closed_counts = 500.0;  ///< ADC counts with the handle fully closed, 0..4095
  double jaw_counts_per_rad = 4000;  ///< counts per rad of opening; negative: the sensor counts down
  double pedal_up_counts = 400.0;    ///< pedal released
  double pedal_down_counts = 3200.0; ///< pedal pressed to its stop

  static std::int32_t Adc(double counts) {
    const double c = std::round(counts);
    return static_cast<std::int32_t>(c < 0.0 ? 0.0 : (c > 4095.0 ? 4095.0 : c));
  }
  /// jaw_rad: the handle's opening (0 closed), already within its mechanical span.
  std::int32_t JawRaw(double jaw_rad) const { return Adc(jaw_closed_counts + jaw_counts_per_rad * jaw_rad); }
  /// travel: 0 released .. 1 pressed to the stop.
  std::int32_t PedalRaw(double travel) const {
    return Adc(pedal_up_counts + travel * (pedal_down_counts - pedal_up_counts));
  }
};

/// Counts of the absolute roll encoder (14 bits a turn) for a sensor angle in rad (any turn).
inline std::int32_t RollRaw(double sensor_rad) {
  constexpr double kTwoPi = 6.283185307179586;
  double a = std::fmod(sensor_rad, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return static_cast<std::int32_t>(std::floor(a / kTwoPi * 16384.0)) % 16384;
}

}  // namespace vesica::fp::emulator
