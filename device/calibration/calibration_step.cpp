#include "device/calibration/calibration_step.h"

#include "device/calibration/calibration_abort.h"

namespace vesica::device::calibration {

void StepContext::RunUntil(const std::function<bool()>& done, double timeout_s, const std::string& what) {
  const double until = link.now_s() + timeout_s;
  double last = link.now_s();
  while (!done()) {
    if (link.now_s() > until) throw CalibrationAbort(AbortReason::kMeasurement, what);
    const double now = link.now_s();
    link.Cycle(servo.Update(link.sample(), now - last > 0 ? now - last : 1e-3));
    last = now;
  }
}

void StepContext::RunFor(double seconds) {
  const double until = link.now_s() + seconds;
  RunUntil([&] { return link.now_s() >= until; }, seconds + 1.0, "timer");
}

}  // namespace vesica::device::calibration
