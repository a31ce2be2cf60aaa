#include "app/calibrate/bus_observer.h"

#include <variant>

#include "firmware_protocol/codec/codec.h"

namespace vesica::app::calibrate {

bool BusObserver::receive(fp::TimedFrame& out) {
  if (!inner_.receive(out)) return false;
  fp::Message m;
  if (fp::decode(out.frame, m) != fp::DecodeError::None) return true;
  if (const auto* hb = std::get_if<fp::Heartbeat>(&m)) {
    heartbeats_[hb->node] = NodeHeartbeat{hb->state, hb->latched_fault};
  } else if (const auto* js = std::get_if<fp::JointState>(&m); js && js->node == recording_node_) {
    const double t = 1e-9 * static_cast<double>(out.timestamp.count());
    if (recorded_.empty() || t - recorded_.back().t_s >= every_s_)
      recorded_.push_back({t, {js->position[0], js->position[1], js->position[2]}});
  }
  return true;
}

const NodeHeartbeat* BusObserver::heartbeat(int node) const {
  const auto it = heartbeats_.find(node);
  return it == heartbeats_.end() ? nullptr : &it->second;
}

void BusObserver::StartRecording(int node, double every_s) {
  recording_node_ = node;
  every_s_ = every_s;
  recorded_.clear();
}

}  // namespace vesica::app::calibrate
