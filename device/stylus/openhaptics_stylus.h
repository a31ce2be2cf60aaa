#pragma once
// The Phantom Omni through OpenHaptics' HD API. Built only when CMake finds HD/hd.h and libHD
// (VESICA_HAVE_OPENHAPTICS); this header needs none of the SDK's.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "device/link_monitor.h"
#include "device/stylus/stylus_device.h"

namespace vesica::device {

struct OpenHapticsStylusConfig {
  std::string device_name;  ///< empty: HD_DEFAULT_DEVICE (the "Default Device" of Touch Setup)
  /// No servo callback, or the HD API reporting an error, for longer than this: link lost. The
  /// HD scheduler runs at 1 kHz; 9 ms keeps the report within 10 ms when Poll runs at 1 kHz.
  std::int64_t loss_timeout_ns = 9'000'000;
  double force_ramp_s = 0.05;
};

/// An Omni (Geomagic Touch) on the HD API. Open() initialises the device, enables force output and
/// starts the HD scheduler with one asynchronous callback at the servo rate: that callback reads
/// the pose and buttons and writes the force inside one hdBeginFrame/hdEndFrame. A cable pulled
/// or a driver error shows as HD errors (hdGetError) or as the callback not running: either makes
/// Status() kLinkLost with the HD error's text, and the callback then writes zero force. Poll()
/// (from the trainer's servo or physics thread) checks the callback's heartbeat.
class OpenHapticsStylus final : public StylusDevice {
 public:
  explicit OpenHapticsStylus(OpenHapticsStylusConfig config = {});
  ~OpenHapticsStylus() override;

  DeviceStatus Open() override;
  void Close() override;
  const StylusCapabilities& StylusCaps() const override { return capabilities_; }
  DeviceStatus Status() const override;
  std::string StatusText() const override;
  StylusState GetStylusState() const override;
  DeviceStatus SetTipForce(const Eigen::Vector3d& f_B) override;
  Eigen::Vector3d RenderedForce() const override;
  DeviceStatus ResetFault() override;

  /// Checks the servo callback's heartbeat against steady_clock; call at 1 kHz.
  void Poll();

  /// Called by the HD scheduler's callback (an implementation detail, public for the C callback).
  void ServoCallback();

 private:
  struct Hd;  // the SDK's handles, kept out of this header
  OpenHapticsStylusConfig config_;
  StylusCapabilities capabilities_;
  std::unique_ptr<Hd> hd_;
  mutable std::mutex mu_;
  LinkMonitor link_;
  bool open_ = false;
  StylusState state_;
  Eigen::Vector3d requested_force_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d rendered_force_ = Eigen::Vector3d::Zero();
  std::int64_t ramp_start_ns_ = 0;
  std::string error_text_;  ///< the last HD error, "" if none
};

}  // namespace vesica::device
