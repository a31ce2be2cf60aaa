// One servo cycle of the UDP stylus on loopback (issue 34): a fake Omni sends a pose datagram,
// UdpStylus::Tick() drains and decodes it and sends a force datagram, the fake Omni reads it.
// The time per iteration is the round trip through the kernel plus our encode/decode, what a
// stylus cycle costs on top of the physics.
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <memory>

#include "device/stylus/udp_stylus.h"

namespace vesica::device {
namespace {

void BM_UdpStylusRoundTrip(benchmark::State& state) {
  std::string error;
  auto probe = UdpDatagramSocket::Open({"127.0.0.1", 0}, {"127.0.0.1", 9}, &error);
  const std::uint16_t device_port = probe ? probe->local_port() : 0;
  probe.reset();
  UdpStylusConfig config;
  config.local.port = 0;
  config.device.port = device_port;
  UdpStylus stylus(config);
  stylus.Open();
  auto device = UdpDatagramSocket::Open({"127.0.0.1", device_port}, {"127.0.0.1", stylus.local_port()}, &error);
  if (!device) {
    state.SkipWithError(error.c_str());
    return;
  }
  OmniPoseDatagram pose;
  pose.p_BTip_B = {0.01, 0.02, 0.03};
  std::array<std::uint8_t, 512> buffer{};
  std::uint64_t forces = 0;
  for (auto _ : state) {
    ++pose.sequence;
    pose.timestamp_ns = std::chrono::steady_clock::now().time_since_epoch().count();
    const auto bytes = EncodeOmniPose(pose);
    device->Send(bytes, &error);
    stylus.Tick();
    stylus.SetTipForce({0.0, 0.5, 0.0});
    bool from_peer = false;
    while (!device->Wait(1'000'000)) {
    }
    for (long n; (n = device->Receive(buffer, &from_peer)) >= 0;) {
      OmniForceDatagram force;
      if (!DecodeOmniForce(std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(n)), &force)) ++forces;
    }
  }
  state.counters["forces_back"] = benchmark::Counter(static_cast<double>(forces), benchmark::Counter::kAvgIterations);
  state.counters["status_ok"] = stylus.Status() == DeviceStatus::kOk ? 1.0 : 0.0;
}
BENCHMARK(BM_UdpStylusRoundTrip)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::device
