#pragma once
// What an Omni-style stylus can do: the HapticDevice capabilities plus its workspace box.

#include <Eigen/Core>

#include "device/haptic_device.h"

namespace vesica::device {

struct StylusCapabilities {
  DeviceCapabilities device;
  /// Usable workspace, an axis-aligned box centred on B's origin: width (x), height (y),
  /// depth (z), m.
  Eigen::Vector3d workspace_box_m = Eigen::Vector3d::Zero();
  double max_continuous_force_N = 0.0;  ///< what the device holds indefinitely (device.max_force_N: peak)
};

/// The Phantom Omni (Geomagic Touch) as specified by its maker: 6-DOF pose in, 3-DOF force out,
/// 3.3 N peak, 0.88 N continuous, 160 x 120 x 70 mm workspace, 1 kHz servo, two buttons.
/// We saturate at the peak force (a needle's capsule peak lasts milliseconds) and let the
/// physics keep sustained forces under the continuous one.
StylusCapabilities PhantomOmniCapabilities();

/// True when p_B (m) lies in the box (boundary included).
bool InsideWorkspace(const StylusCapabilities& caps, const Eigen::Vector3d& p_B);

/// p_B clamped into the box.
Eigen::Vector3d ClampToWorkspace(const StylusCapabilities& caps, const Eigen::Vector3d& p_B);

}  // namespace vesica::device
