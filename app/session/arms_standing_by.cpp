#include "app/session/arms_standing_by.h"

#include <utility>

namespace vesica::app {

ArmsStandingBy::ArmsStandingBy(std::array<device::HapticDevice*, 2> devices, std::function<void()> servo)
    : devices_(devices), servo_(std::move(servo)) {}

void ArmsStandingBy::ServoTick() {
  if (servo_) servo_();
}

bool ArmsStandingBy::ToolPoint(int /*instrument*/, Eigen::Vector3d& /*p_W*/) { return false; }

void ArmsStandingBy::SetForce(int instrument, const Eigen::Vector3d& /*f_W*/) {
  device::HapticDevice* d = devices_.at(static_cast<size_t>(instrument));
  if (d != nullptr) d->SetTipForce(Eigen::Vector3d::Zero());
}

}  // namespace vesica::app
