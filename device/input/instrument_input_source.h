#pragma once

#include "device/input/input_frame.h"

namespace vesica::device {

/// What any instrument input gives the physics step: keyboard, replay, CAN arm. Sample() is
/// called once per physics step with that step's time; the returned frame carries time_s.
class InstrumentInputSource {
 public:
  virtual ~InstrumentInputSource() = default;
  virtual InputFrame Sample(double time_s) = 0;
};

}  // namespace vesica::device
