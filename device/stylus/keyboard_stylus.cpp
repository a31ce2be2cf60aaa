#include "device/stylus/keyboard_stylus.h"

#include <Eigen/Geometry>
#include <cctype>
#include <stdexcept>

#include "device/stylus/stylus_force.h"

namespace vesica::device {

KeyboardStylus::KeyboardStylus(const StylusState& initial, KeyboardStylusStep step, StylusCapabilities capabilities)
    : step_(step), capabilities_(std::move(capabilities)) {
  if (auto problem = StylusStateProblem(initial)) throw std::invalid_argument("KeyboardStylus: " + *problem);
  state_ = NormalizedStylus(initial);
  state_.p_BTip_B = ClampToWorkspace(capabilities_, state_.p_BTip_B);
}

DeviceStatus KeyboardStylus::Open() {
  std::lock_guard lock(mu_);
  if (open_) return DeviceStatus::kAlreadyOpen;
  open_ = true;
  return DeviceStatus::kOk;
}

void KeyboardStylus::Close() {
  std::lock_guard lock(mu_);
  open_ = false;
  force_.setZero();
}

DeviceStatus KeyboardStylus::Status() const {
  std::lock_guard lock(mu_);
  return open_ ? DeviceStatus::kOk : DeviceStatus::kNotOpen;
}

std::string KeyboardStylus::StatusText() const {
  return Status() == DeviceStatus::kOk ? "keyboard and mouse stylus: ok (no force is felt)"
                                       : "keyboard and mouse stylus: not open";
}

StylusState KeyboardStylus::GetStylusState() const {
  std::lock_guard lock(mu_);
  return state_;
}

DeviceStatus KeyboardStylus::SetTipForce(const Eigen::Vector3d& f_B) {
  if (ForceProblem(f_B)) return DeviceStatus::kInvalidArgument;
  std::lock_guard lock(mu_);
  if (!open_) return DeviceStatus::kNotOpen;
  force_ = SaturateForce(f_B, capabilities_.device.max_force_N);
  return DeviceStatus::kOk;
}

Eigen::Vector3d KeyboardStylus::RenderedForce() const {
  std::lock_guard lock(mu_);
  return open_ ? force_ : Eigen::Vector3d::Zero();
}

void KeyboardStylus::MoveLocked(const Eigen::Vector3d& delta_B) {
  state_.p_BTip_B = ClampToWorkspace(capabilities_, state_.p_BTip_B + delta_B);
}

bool KeyboardStylus::ApplyKey(char key) {
  const char k = static_cast<char>(std::tolower(static_cast<unsigned char>(key)));
  std::lock_guard lock(mu_);
  const double t = step_.translation_m;
  const double a = step_.angle_rad;
  switch (k) {
    case 'a':
      MoveLocked({-t, 0, 0});
      return true;
    case 'd':
      MoveLocked({t, 0, 0});
      return true;
    case 'r':
      MoveLocked({0, t, 0});
      return true;
    case 'f':
      MoveLocked({0, -t, 0});
      return true;
    case 'w':
      MoveLocked({0, 0, -t});
      return true;
    case 's':
      MoveLocked({0, 0, t});
      return true;
    case 'q':
      MoveLocked(t * state_.d_B);
      return true;
    case 'e':
      MoveLocked(-t * state_.d_B);
      return true;
    case 'j':
    case 'l': {
      // Turning left (j) carries the tip toward -x: a positive turn about +y for a stylus along -z.
      const double angle = k == 'j' ? a : -a;
      state_.d_B = (Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()) * state_.d_B).normalized();
      return true;
    }
    case 'i':
    case 'k': {
      // Tilt about the horizontal axis normal to the stylus; a vertical stylus tilts about x.
      Eigen::Vector3d axis = state_.d_B.cross(Eigen::Vector3d::UnitY());  // i raises the tip
      if (axis.norm() < 1e-9) axis = Eigen::Vector3d::UnitX();
      const double angle = k == 'i' ? a : -a;
      state_.d_B = (Eigen::AngleAxisd(angle, axis.normalized()) * state_.d_B).normalized();
      return true;
    }
    default:
      return false;
  }
}

void KeyboardStylus::ApplyDrag(double dx_px, double dy_px) {
  std::lock_guard lock(mu_);
  MoveLocked({dx_px * step_.translation_m_per_pixel, -dy_px * step_.translation_m_per_pixel, 0});
}

void KeyboardStylus::ApplyWheel(double notches) {
  std::lock_guard lock(mu_);
  MoveLocked(notches * step_.advance_m_per_wheel_notch * state_.d_B);
}

bool KeyboardStylus::SetButton(int button, bool pressed) {
  if (button != 1 && button != 2) return false;
  const std::uint32_t bit = button == 1 ? kStylusButton1 : kStylusButton2;
  std::lock_guard lock(mu_);
  state_.buttons = pressed ? (state_.buttons | bit) : (state_.buttons & ~bit);
  return true;
}

bool KeyboardStylus::SetPose(const StylusState& state, std::string* error) {
  if (auto problem = StylusStateProblem(state)) {
    *error = "keyboard stylus: " + *problem;
    return false;
  }
  std::lock_guard lock(mu_);
  state_ = NormalizedStylus(state);
  state_.p_BTip_B = ClampToWorkspace(capabilities_, state_.p_BTip_B);
  return true;
}

const char* KeyboardStylusHelp() {
  return "Stylus: A/D left/right, R/F up/down, W/S away/toward, J/L turn, I/K tilt, Q/E advance/withdraw, "
         "drag to move, wheel to advance";
}

}  // namespace vesica::device
