#pragma once

#include <cstddef>
#include <mutex>

#include "device/stylus/stylus_device.h"
#include "device/stylus/stylus_recording.h"

namespace vesica::device {

/// Replays a recorded stylus stream as a stylus device. Seek(t) sets the time: P is linearly
/// interpolated between the samples around t, D likewise and made unit again, buttons hold the
/// value of the sample at or before t. Before the first sample it gives the first, after the last
/// the last. A pure function of t, so a replay is deterministic whatever order it is sampled in.
/// Forces are accepted (saturated) and reported by RenderedForce, felt by nobody.
class ReplayStylus final : public StylusDevice {
 public:
  /// std::invalid_argument for an empty recording or one with a StylusSampleProblem.
  explicit ReplayStylus(StylusRecording recording, StylusCapabilities capabilities = PhantomOmniCapabilities());

  DeviceStatus Open() override;
  void Close() override;
  const StylusCapabilities& StylusCaps() const override { return capabilities_; }
  DeviceStatus Status() const override;
  std::string StatusText() const override;
  StylusState GetStylusState() const override;
  DeviceStatus SetTipForce(const Eigen::Vector3d& f_B) override;
  Eigen::Vector3d RenderedForce() const override;
  DeviceStatus ResetFault() override { return Status(); }

  /// t must not be NaN (kInvalidArgument, the state unchanged).
  DeviceStatus Seek(double time_s);
  /// The state at t without changing the device (the same interpolation Seek uses).
  StylusState SampleAt(double time_s) const;

  double start_time_s() const { return recording_.samples.front().time_s; }
  double end_time_s() const { return recording_.samples.back().time_s; }
  bool finished(double time_s) const { return time_s > end_time_s(); }
  const StylusRecording& recording() const { return recording_; }

 private:
  StylusRecording recording_;
  StylusCapabilities capabilities_;
  mutable std::mutex mu_;
  bool open_ = false;
  double time_s_ = 0;
  StylusState state_;
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();
};

}  // namespace vesica::device
