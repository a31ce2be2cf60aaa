#include "device/stylus/udp_stylus.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "device/stylus/stylus_force.h"

namespace vesica::device {
namespace {

std::int64_t SteadyNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Serial-number order on the 32-bit sequence: a is after b when a - b, read signed, is > 0.
bool SequenceAfter(std::uint32_t a, std::uint32_t b) { return static_cast<std::int32_t>(a - b) > 0; }

}  // namespace

UdpStylus::UdpStylus(UdpStylusConfig config) : config_(std::move(config)), link_(config_.loss_timeout_ns) {
  if (config_.loss_timeout_ns <= 0) throw std::invalid_argument("UdpStylusConfig: loss_timeout_ns must be > 0");
  if (!(config_.force_ramp_s >= 0)) throw std::invalid_argument("UdpStylusConfig: force_ramp_s must be >= 0");
}

DeviceStatus UdpStylus::Open() {
  std::lock_guard lock(mu_);
  if (socket_) return DeviceStatus::kAlreadyOpen;
  std::string error;
  socket_ = UdpDatagramSocket::Open(config_.local, config_.device, &error);
  if (!socket_) {
    last_error_ = config_.name + ": " + error;
    return DeviceStatus::kTransportError;
  }
  last_error_.clear();
  link_ = LinkMonitor(config_.loss_timeout_ns);
  have_pose_ = false;
  requested_force_.setZero();
  return DeviceStatus::kConnecting;
}

void UdpStylus::Close() {
  std::lock_guard lock(mu_);
  if (socket_) {
    // Leave the device with zero force rather than with whatever it rendered last.
    OmniForceDatagram zero;
    zero.sequence = ++force_sequence_;
    zero.pose_sequence = last_sequence_;
    zero.timestamp_ns = SteadyNowNs();
    std::string error;
    const auto bytes = EncodeOmniForce(zero);
    socket_->Send(bytes, &error);
  }
  socket_.reset();
  requested_force_.setZero();
  last_error_.clear();
}

DeviceStatus UdpStylus::StatusLocked() const {
  if (!socket_) return last_error_.empty() ? DeviceStatus::kNotOpen : DeviceStatus::kTransportError;
  if (!link_.ever_seen()) return DeviceStatus::kConnecting;
  if (!link_.up()) return DeviceStatus::kLinkLost;
  return DeviceStatus::kOk;
}

DeviceStatus UdpStylus::Status() const {
  std::lock_guard lock(mu_);
  return StatusLocked();
}

std::string UdpStylus::StatusText() const {
  std::lock_guard lock(mu_);
  const std::string where = config_.name + " on UDP " + config_.local.address + ":" +
                            std::to_string(socket_ ? socket_->local_port() : config_.local.port);
  char buf[256];
  switch (StatusLocked()) {
    case DeviceStatus::kOk:
      return where + ": ok";
    case DeviceStatus::kNotOpen:
      return where + ": not open";
    case DeviceStatus::kTransportError:
      return where + ": " + last_error_;
    case DeviceStatus::kConnecting:
      return where + ": waiting for the first pose datagram (is vesica-omnisim running, sending to this port?)";
    case DeviceStatus::kLinkLost:
      std::snprintf(buf, sizeof buf,
                    ": no pose datagram for %.1f ms (last sequence %u, limit %.1f ms): link lost, "
                    "force off",
                    1e-6 * static_cast<double>(link_lost_at_ns_ - link_.last_state_ns()), last_sequence_,
                    1e-6 * static_cast<double>(config_.loss_timeout_ns));
      return where + buf;
    default:
      return where + ": " + std::string(ToString(StatusLocked()));
  }
}

StylusState UdpStylus::GetStylusState() const {
  std::lock_guard lock(mu_);
  return state_;
}

DeviceStatus UdpStylus::SetTipForce(const Eigen::Vector3d& f_B) {
  if (ForceProblem(f_B)) return DeviceStatus::kInvalidArgument;
  std::lock_guard lock(mu_);
  const DeviceStatus status = StatusLocked();
  // Off-line requests are refused, not kept: force restarts from zero when the link returns.
  if (status != DeviceStatus::kOk) return status;
  requested_force_ = SaturateForce(f_B, config_.capabilities.device.max_force_N);
  return DeviceStatus::kOk;
}

Eigen::Vector3d UdpStylus::RenderedForceLocked(std::int64_t now_ns) const {
  if (StatusLocked() != DeviceStatus::kOk) return Eigen::Vector3d::Zero();
  if (config_.force_ramp_s <= 0) return requested_force_;
  const double ramp = std::clamp(1e-9 * static_cast<double>(now_ns - ramp_start_ns_) / config_.force_ramp_s, 0.0, 1.0);
  return ramp * requested_force_;
}

Eigen::Vector3d UdpStylus::RenderedForce() const {
  std::lock_guard lock(mu_);
  return RenderedForceLocked(last_tick_ns_);
}

void UdpStylus::Tick() { Tick(SteadyNowNs()); }

void UdpStylus::Tick(std::int64_t now_ns) {
  std::lock_guard lock(mu_);
  if (!socket_) return;
  last_tick_ns_ = now_ns;
  std::array<std::uint8_t, 512> buffer{};
  bool from_peer = false;
  for (long n; (n = socket_->Receive(buffer, &from_peer)) >= 0;) {
    if (static_cast<std::size_t>(n) > buffer.size()) {  // truncated: far longer than any datagram of ours
      ++rejected_;
      last_rejection_ = "Omni datagram: " + std::to_string(n) + " bytes, far too long";
      continue;
    }
    HandleDatagram(std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(n)), from_peer, now_ns);
  }
  if (link_.Poll(now_ns) == LinkMonitor::Event::kLost) {
    link_lost_at_ns_ = now_ns;
    requested_force_.setZero();
  }
  OmniForceDatagram out;
  out.sequence = ++force_sequence_;
  out.pose_sequence = last_sequence_;
  out.timestamp_ns = now_ns;
  out.f_B = RenderedForceLocked(now_ns);
  std::string error;
  const auto bytes = EncodeOmniForce(out);
  if (socket_->Send(bytes, &error)) {
    ++forces_sent_;
  } else {
    last_error_ = error;
  }
}

void UdpStylus::HandleDatagram(std::span<const std::uint8_t> bytes, bool from_peer, std::int64_t now_ns) {
  auto reject = [&](std::string why) {
    ++rejected_;
    last_rejection_ = std::move(why);
  };
  if (!from_peer)
    return reject("a datagram from another address than " + config_.device.address + ":" +
                  std::to_string(config_.device.port));
  OmniPoseDatagram pose;
  if (auto problem = DecodeOmniPose(bytes, &pose)) return reject(*problem);
  // While the link is up, a sequence not after the last is a duplicate or reordered: dropped.
  // After a loss any sequence is taken (a restarted emulator counts from 0 again).
  if (have_pose_ && link_.up() && !SequenceAfter(pose.sequence, last_sequence_)) {
    return reject("Omni pose datagram: sequence " + std::to_string(pose.sequence) + " not after " +
                  std::to_string(last_sequence_) + " (duplicate or reordered)");
  }
  const bool was_up = link_.up();
  link_.OnState(now_ns);
  if (!was_up) {
    ramp_start_ns_ = now_ns;
    requested_force_.setZero();
  }
  state_.p_BTip_B = pose.p_BTip_B;
  state_.d_B = pose.d_B.normalized();
  state_.buttons = pose.buttons;
  state_.timestamp_ns = pose.timestamp_ns;
  last_sequence_ = pose.sequence;
  last_pose_age_ns_ = now_ns - pose.timestamp_ns;
  have_pose_ = true;
  ++poses_received_;
}

std::uint16_t UdpStylus::local_port() const {
  std::lock_guard lock(mu_);
  return socket_ ? socket_->local_port() : 0;
}
std::int64_t UdpStylus::last_pose_arrival_ns() const {
  std::lock_guard lock(mu_);
  return link_.last_state_ns();
}
std::uint32_t UdpStylus::last_pose_sequence() const {
  std::lock_guard lock(mu_);
  return last_sequence_;
}
std::int64_t UdpStylus::link_lost_at_ns() const {
  std::lock_guard lock(mu_);
  return link_lost_at_ns_;
}
std::uint32_t UdpStylus::link_loss_count() const {
  std::lock_guard lock(mu_);
  return link_.loss_count();
}
std::uint32_t UdpStylus::link_restore_count() const {
  std::lock_guard lock(mu_);
  return link_.restore_count();
}
std::uint64_t UdpStylus::poses_received() const {
  std::lock_guard lock(mu_);
  return poses_received_;
}
std::uint64_t UdpStylus::datagrams_rejected() const {
  std::lock_guard lock(mu_);
  return rejected_;
}
std::string UdpStylus::last_rejection() const {
  std::lock_guard lock(mu_);
  return last_rejection_;
}
std::uint64_t UdpStylus::forces_sent() const {
  std::lock_guard lock(mu_);
  return forces_sent_;
}
std::string UdpStylus::last_error() const {
  std::lock_guard lock(mu_);
  return last_error_;
}
std::int64_t UdpStylus::last_pose_age_ns() const {
  std::lock_guard lock(mu_);
  return last_pose_age_ns_;
}

}  // namespace vesica::device
