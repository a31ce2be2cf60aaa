#pragma once

#include <string>

#include "device/haptic_device.h"
#include "device/stylus/stylus_capabilities.h"
#include "device/stylus/stylus_state.h"

namespace vesica::device {

/// One instrument interface for a stylus device (Omni emulator over UDP, OpenHaptics, keyboard
/// and mouse, replay): position P, direction D, two buttons, force out. A HapticDevice, so the
/// session can treat it as it treats an arm; the stylus-specific face is GetStylusState().
///
/// Every backend: SetTipForce rejects non-finite forces with kInvalidArgument (the force in use
/// unchanged), saturates to Capabilities().max_force_N with the direction kept, and renders zero
/// force whenever Status() is not kOk. StatusText() says why in words a trainee can act on.
class StylusDevice : public HapticDevice {
 public:
  const DeviceCapabilities& Capabilities() const final { return StylusCaps().device; }
  virtual const StylusCapabilities& StylusCaps() const = 0;

  /// The latest valid sample (D unit). Before the first one: the default StylusState.
  virtual StylusState GetStylusState() const = 0;
  /// Status() in words, with the reason when it is not kOk ("Omni emulator on UDP 127.0.0.1:
  /// 21001: no datagram for 9.3 ms (last sequence 4711): link lost, force off").
  virtual std::string StatusText() const = 0;
  /// The force the device renders now (N, base frame): zero when not kOk.
  virtual Eigen::Vector3d RenderedForce() const = 0;

  /// No joint state: an Omni reports its pose. count = 0.
  JointState GetJointState() const override { return {}; }
  ToolState GetToolState() const override { return ToolStateFromStylus(GetStylusState()); }
};

}  // namespace vesica::device
