// The hand sensors as the node reports them (AuxState), with the guided hand calibration stored
// in image layout 2 applied: roll less the sensor's mounting offset, the jaw's opening from its
// ADC normalised to the measured span (0 closed .. jaw_open_rad open), the pedal pressed past half
// its measured travel. A value not measured (closed = open, released = pressed; a layout-1 image)
// stays as the board converts it.
// Use: const HandReading h = calibrated_hand(params, sample);
// Freestanding C++17, header-only.
#pragma once

#include <cstdint>

#include "firmware_protocol/node/node_hardware.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::fp {

struct HandReading {
  float roll_rad = 0;  // (-pi, pi]
  float jaw_rad = 0;   // 0 .. jaw_open_rad
  bool pedal = false;
};

inline HandReading calibrated_hand(const ParameterStore& p, const HardwareSample& s) {
  constexpr float kPi = 3.14159265f;
  HandReading h{s.roll_rad, s.jaw_rad, s.pedal};
  float roll = s.roll_rad - p.f32(param::kRollSensorOffset);
  if (roll > kPi) roll -= 2.0f * kPi;
  if (roll <= -kPi) roll += 2.0f * kPi;
  h.roll_rad = roll;
  const float closed = static_cast<float>(p.u32(param::kJawClosedCounts));
  const float open = static_cast<float>(p.u32(param::kJawOpenCounts));
  if (open != closed) {
    float fraction = (static_cast<float>(s.jaw_raw) - closed) / (open - closed);
    fraction = fraction < 0.0f ? 0.0f : (fraction > 1.0f ? 1.0f : fraction);
    h.jaw_rad = fraction * p.f32(param::kJawOpen_rad);
  }
  const float released = static_cast<float>(p.u32(param::kPedalReleasedCounts));
  const float pressed = static_cast<float>(p.u32(param::kPedalPressedCounts));
  if (pressed != released) h.pedal = (static_cast<float>(s.pedal_raw) - released) / (pressed - released) > 0.5f;
  return h;
}

}  // namespace vesica::fp
