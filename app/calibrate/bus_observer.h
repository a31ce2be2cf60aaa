// A transport decorator that watches what the nodes say as the calibration tool's frames pass:
// each node's NMT state and latched fault from its heartbeats (CalibrationLink keeps them private)
// and, while recording, the joint positions (the range sweep's plot).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "firmware_protocol/codec/protocol_enums.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::app::calibrate {

struct NodeHeartbeat {
  fp::NodeState state = fp::NodeState::Boot;
  fp::FaultCode latched_fault = fp::FaultCode::None;
};

struct PositionSample {
  double t_s = 0.0;
  std::array<double, 3> position{};
};

class BusObserver final : public fp::Transport {
 public:
  explicit BusObserver(fp::Transport& inner) : inner_(inner) {}

  fp::SendStatus send(const fp::CanFrame& frame, fp::Nanoseconds deadline) override {
    return inner_.send(frame, deadline);
  }
  bool receive(fp::TimedFrame& out) override;
  bool poll_event(fp::BusEvent& out) override { return inner_.poll_event(out); }
  bool wait(fp::Nanoseconds timeout) override { return inner_.wait(timeout); }
  fp::Nanoseconds now() const override { return inner_.now(); }
  fp::BusState state() const override { return inner_.state(); }
  fp::TransportStats stats() const override { return inner_.stats(); }

  /// The last heartbeat of `node`, if one came.
  const NodeHeartbeat* heartbeat(int node) const;
  /// Joint states of `node` are kept (one per `every_s`) from now until StopRecording().
  void StartRecording(int node, double every_s);
  void StopRecording() { recording_node_ = -1; }
  const std::vector<PositionSample>& recorded() const { return recorded_; }
  void ClearRecording() { recorded_.clear(); }

 private:
  fp::Transport& inner_;
  std::map<int, NodeHeartbeat> heartbeats_;
  int recording_node_ = -1;
  double every_s_ = 0.01;
  std::vector<PositionSample> recorded_;
};

}  // namespace vesica::app::calibrate
