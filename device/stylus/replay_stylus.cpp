#include "device/stylus/replay_stylus.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "device/stylus/stylus_force.h"

namespace vesica::device {

ReplayStylus::ReplayStylus(StylusRecording recording, StylusCapabilities capabilities)
    : recording_(std::move(recording)), capabilities_(std::move(capabilities)) {
  if (recording_.samples.empty()) throw std::invalid_argument("ReplayStylus: recording has no samples");
  for (std::size_t i = 0; i < recording_.samples.size(); ++i) {
    const StylusSample* previous = i == 0 ? nullptr : &recording_.samples[i - 1];
    if (auto problem = StylusSampleProblem(recording_.samples[i], previous)) {
      throw std::invalid_argument("ReplayStylus: sample " + std::to_string(i) + ": " + *problem);
    }
    recording_.samples[i].state = NormalizedStylus(recording_.samples[i].state);
  }
  time_s_ = start_time_s();
  state_ = recording_.samples.front().state;
}

DeviceStatus ReplayStylus::Open() {
  std::lock_guard lock(mu_);
  if (open_) return DeviceStatus::kAlreadyOpen;
  open_ = true;
  return DeviceStatus::kOk;
}

void ReplayStylus::Close() {
  std::lock_guard lock(mu_);
  open_ = false;
  force_.setZero();
}

DeviceStatus ReplayStylus::Status() const {
  std::lock_guard lock(mu_);
  return open_ ? DeviceStatus::kOk : DeviceStatus::kNotOpen;
}

std::string ReplayStylus::StatusText() const {
  std::lock_guard lock(mu_);
  char buf[128];
  std::snprintf(buf, sizeof buf, "stylus replay: %s at t = %.3f s of %.3f s", open_ ? "ok" : "not open", time_s_,
                end_time_s());
  return buf;
}

StylusState ReplayStylus::GetStylusState() const {
  std::lock_guard lock(mu_);
  return state_;
}

DeviceStatus ReplayStylus::SetTipForce(const Eigen::Vector3d& f_B) {
  if (ForceProblem(f_B)) return DeviceStatus::kInvalidArgument;
  std::lock_guard lock(mu_);
  if (!open_) return DeviceStatus::kNotOpen;
  force_ = SaturateForce(f_B, capabilities_.device.max_force_N);
  return DeviceStatus::kOk;
}

Eigen::Vector3d ReplayStylus::RenderedForce() const {
  std::lock_guard lock(mu_);
  return open_ ? force_ : Eigen::Vector3d::Zero();
}

StylusState ReplayStylus::SampleAt(double time_s) const {
  const std::vector<StylusSample>& s = recording_.samples;
  if (!(time_s > s.front().time_s)) return s.front().state;
  if (time_s >= s.back().time_s) return s.back().state;
  const auto after = std::upper_bound(s.begin(), s.end(), time_s,
                                      [](double t, const StylusSample& sample) { return t < sample.time_s; });
  const StylusSample& b = *after;
  const StylusSample& a = *(after - 1);
  const double alpha = (time_s - a.time_s) / (b.time_s - a.time_s);
  StylusState out;
  out.p_BTip_B = a.state.p_BTip_B + alpha * (b.state.p_BTip_B - a.state.p_BTip_B);
  const Eigen::Vector3d d = a.state.d_B + alpha * (b.state.d_B - a.state.d_B);
  // Opposite directions in consecutive samples would interpolate through zero: keep a's there.
  out.d_B = d.norm() < kMinDirectionNorm ? a.state.d_B : d.normalized();
  out.buttons = a.state.buttons;
  out.timestamp_ns = static_cast<std::int64_t>(std::llround(time_s * 1e9));
  return out;
}

DeviceStatus ReplayStylus::Seek(double time_s) {
  if (std::isnan(time_s)) return DeviceStatus::kInvalidArgument;
  const StylusState state = SampleAt(time_s);
  std::lock_guard lock(mu_);
  time_s_ = time_s;
  state_ = state;
  return DeviceStatus::kOk;
}

}  // namespace vesica::device
