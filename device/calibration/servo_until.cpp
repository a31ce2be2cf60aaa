#include "device/calibration/servo_until.h"

#include "device/calibration/calibration_abort.h"

namespace vesica::device::calibration {

void ServoUntil(CalibrationLink& link, JointServo& servo, const std::function<bool()>& done, double timeout_s,
                const std::string& what) {
  const double until = link.now_s() + timeout_s;
  double last = link.now_s();
  while (!done()) {
    if (link.now_s() > until) throw CalibrationAbort(AbortReason::kMeasurement, what);
    const double now = link.now_s();
    link.Cycle(servo.Update(link.sample(), now - last > 0 ? now - last : 1e-3));  // 1 ms when the clock stood still
    last = now;
  }
}

}  // namespace vesica::device::calibration
