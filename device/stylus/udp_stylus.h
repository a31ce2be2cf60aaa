#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "device/link_monitor.h"
#include "device/stylus/omni_datagram.h"
#include "device/stylus/stylus_device.h"
#include "device/stylus/udp_datagram_socket.h"

namespace vesica::device {

struct UdpStylusConfig {
  UdpEndpoint local{"127.0.0.1", 21001};   ///< where pose datagrams arrive (vesica-omnisim --host-port)
  UdpEndpoint device{"127.0.0.1", 21000};  ///< where force datagrams go (vesica-omnisim --port)
  /// No valid pose datagram for longer than this: link lost, force off. 9 ms so that, checked
  /// every 1 kHz Tick, a loss is reported within 10 ms of the last datagram.
  std::int64_t loss_timeout_ns = 9'000'000;
  /// After (re)connection the force fades in from zero over this, s (>= 0).
  double force_ramp_s = 0.05;
  StylusCapabilities capabilities = PhantomOmniCapabilities();
  std::string name = "Omni emulator";  ///< how StatusText names the device
};

/// The host side of an Omni-style stylus over UDP (vesica-omnisim, or a real Omni behind a small
/// bridge speaking docs/omni.md). Tick() is one servo cycle: drain every waiting pose datagram
/// (garbage is counted and its reason kept, the state untouched), keep the link, then send one
/// force datagram (zero unless Status() is kOk).
///
/// Loss: no valid pose for loss_timeout_ns -> kLinkLost at that Tick: the requested force is
/// cleared and zero is sent from then on. The first valid pose after that restores kOk (a
/// restarted emulator's sequence starts afresh), and force restarts from zero: nothing is
/// rendered until SetTipForce is called again, and that fades in over force_ramp_s.
///
/// Times are the host's CLOCK_MONOTONIC (steady_clock) in ns: Tick() reads it, Tick(now_ns)
/// takes it from the caller (tests, a servo loop that already read the clock); a datagram's
/// arrival time is the now of the Tick that drained it. Thread-safe: Tick() from the servo
/// thread, the rest from any thread.
class UdpStylus final : public StylusDevice {
 public:
  /// std::invalid_argument for loss_timeout_ns <= 0 or a negative or NaN force_ramp_s.
  explicit UdpStylus(UdpStylusConfig config);

  /// Binds the local port; kTransportError (last_error() says why) when it cannot. Then
  /// kConnecting until the first pose arrives.
  DeviceStatus Open() override;
  void Close() override;
  const StylusCapabilities& StylusCaps() const override { return config_.capabilities; }
  DeviceStatus Status() const override;
  std::string StatusText() const override;
  StylusState GetStylusState() const override;
  DeviceStatus SetTipForce(const Eigen::Vector3d& f_B) override;
  Eigen::Vector3d RenderedForce() const override;
  /// Nothing latches on this link: kOk when up, else the status.
  DeviceStatus ResetFault() override { return Status(); }

  void Tick();
  void Tick(std::int64_t now_ns);

  // Diagnostics.
  std::uint16_t local_port() const;
  std::int64_t last_pose_arrival_ns() const;  ///< host time of the last valid pose, 0 before one
  std::uint32_t last_pose_sequence() const;
  /// When (host time) the last loss was reported; 0 if never.
  std::int64_t link_lost_at_ns() const;
  std::uint32_t link_loss_count() const;
  std::uint32_t link_restore_count() const;
  std::uint64_t poses_received() const;
  std::uint64_t datagrams_rejected() const;  ///< garbage, foreign or stale datagrams dropped
  std::string last_rejection() const;        ///< why the last one was dropped; empty if none
  std::uint64_t forces_sent() const;
  std::string last_error() const;
  /// Host time minus the device's timestamp of the last pose, ns (one-way latency when both
  /// clocks are this host's CLOCK_MONOTONIC, as with vesica-omnisim).
  std::int64_t last_pose_age_ns() const;

 private:
  void HandleDatagram(std::span<const std::uint8_t> bytes, bool from_peer, std::int64_t now_ns);
  DeviceStatus StatusLocked() const;
  Eigen::Vector3d RenderedForceLocked(std::int64_t now_ns) const;

  UdpStylusConfig config_;
  mutable std::mutex mu_;
  std::unique_ptr<UdpDatagramSocket> socket_;
  LinkMonitor link_;
  StylusState state_;
  bool have_pose_ = false;
  std::uint32_t last_sequence_ = 0;
  std::int64_t last_pose_age_ns_ = 0;
  std::int64_t link_lost_at_ns_ = 0;
  std::int64_t ramp_start_ns_ = 0;
  std::int64_t last_tick_ns_ = 0;
  Eigen::Vector3d requested_force_ = Eigen::Vector3d::Zero();
  std::uint32_t force_sequence_ = 0;
  std::uint64_t poses_received_ = 0;
  std::uint64_t rejected_ = 0;
  std::uint64_t forces_sent_ = 0;
  std::string last_rejection_;
  std::string last_error_;
};

}  // namespace vesica::device
