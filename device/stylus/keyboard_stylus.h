#pragma once
// A stylus driven from the keyboard and mouse, for training without an Omni. Plain logic, no Qt:
// the GUI maps its key and mouse events to these calls (an ASCII character per key).
//
//   A/D  tip left/right (x)      R/F  up/down (y)          W/S  away from/toward the user (z)
//   J/L  turn the stylus left/right (about y)   I/K  tilt it up/down
//   Q/E  advance/withdraw along the stylus (the needle's insertion)
//   mouse drag: tip in the screen plane (x right, y up);  wheel: advance/withdraw
//   buttons: SetButton (the GUI holds button 1 on Space, button 2 on B, say)

#include <mutex>

#include "device/stylus/stylus_device.h"

namespace vesica::device {

struct KeyboardStylusStep {
  double translation_m = 0.001;             ///< per key press, > 0
  double angle_rad = 0.034906585039886591;  ///< per key press (2 degrees), > 0
  double translation_m_per_pixel = 0.0001;  ///< mouse drag
  double advance_m_per_wheel_notch = 0.001;
};

class KeyboardStylus final : public StylusDevice {
 public:
  /// Starts at `initial` (checked: std::invalid_argument naming the problem), clamped into the
  /// workspace.
  explicit KeyboardStylus(const StylusState& initial = {}, KeyboardStylusStep step = {},
                          StylusCapabilities capabilities = PhantomOmniCapabilities());

  DeviceStatus Open() override;
  void Close() override;
  const StylusCapabilities& StylusCaps() const override { return capabilities_; }
  DeviceStatus Status() const override;
  std::string StatusText() const override;
  StylusState GetStylusState() const override;
  /// Kept (saturated) so the GUI can draw the force the trainee would feel.
  DeviceStatus SetTipForce(const Eigen::Vector3d& f_B) override;
  Eigen::Vector3d RenderedForce() const override;
  DeviceStatus ResetFault() override { return Status(); }

  /// One key (case-insensitive). False when it is not a stylus key (nothing changes).
  bool ApplyKey(char key);
  /// A drag of (dx, dy) pixels, x right, y down on the screen.
  void ApplyDrag(double dx_px, double dy_px);
  /// Wheel notches, positive away from the user: advance along the stylus.
  void ApplyWheel(double notches);
  /// button: 1 or 2 (false for any other); pressed or released.
  bool SetButton(int button, bool pressed);
  /// Puts the stylus at `state`; a StylusStateProblem is refused (false, *error says why) and
  /// the stylus stays where it was.
  bool SetPose(const StylusState& state, std::string* error);

 private:
  void MoveLocked(const Eigen::Vector3d& delta_B);

  KeyboardStylusStep step_;
  StylusCapabilities capabilities_;
  mutable std::mutex mu_;
  bool open_ = false;
  StylusState state_;
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();
};

/// The one-line key summary for the status bar.
const char* KeyboardStylusHelp();

}  // namespace vesica::device
