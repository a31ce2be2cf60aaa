#include "physics/grasp/grasp_state_machine.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

GraspStateMachine::GraspStateMachine(const GraspSettings& s) : settings_(s) {
  if (!(s.close_angle >= 0.0 && s.open_angle > s.close_angle))
    throw std::invalid_argument("GraspSettings: need 0 <= close_angle < open_angle (rad)");
  if (!(s.slip_distance > 0.0)) throw std::invalid_argument("GraspSettings: slip_distance must be > 0 m");
  if (!(s.friction_limit > 0.0)) throw std::invalid_argument("GraspSettings: friction_limit must be > 0 N");
}

GraspEvents GraspStateMachine::Update(const GraspInput& in) {
  if (!std::isfinite(in.jaw_angle)) throw std::invalid_argument("GraspStateMachine::Update: jaw_angle is not finite");
  GraspEvents events;
  const bool closed = in.jaw_angle <= settings_.close_angle;
  const bool open = in.jaw_angle >= settings_.open_angle;
  switch (state_) {
    case State::kOpen:
      if (!closed) break;
      if (in.hits.empty()) {
        state_ = State::kClosedEmpty;
        break;
      }
      for (const SurfaceHit& h : in.hits) points_.push_back({h.surface, h.triangle, h.weights});
      state_ = State::kHolding;
      events.grasped = true;
      break;
    case State::kClosedEmpty:
      if (open) state_ = State::kOpen;
      break;
    case State::kHolding: {
      if (open) {
        points_.clear();
        state_ = State::kOpen;
        events.released = true;
        break;
      }
      if (in.grasped_positions.size() != points_.size() || in.constraint_forces.size() != points_.size())
        throw std::invalid_argument("GraspStateMachine::Update: holding " + std::to_string(points_.size()) +
                                    " points but got " + std::to_string(in.grasped_positions.size()) +
                                    " positions and " + std::to_string(in.constraint_forces.size()) + " forces");
      std::vector<GraspPoint> kept;
      for (size_t i = 0; i < points_.size(); ++i) {
        const bool too_far = (in.grasped_positions[i] - in.jaw_position).norm() > settings_.slip_distance;
        const bool too_hard = in.constraint_forces[i] > settings_.friction_limit;
        if (too_far || too_hard)
          ++events.slipped;
        else
          kept.push_back(points_[i]);
      }
      points_ = std::move(kept);
      total_slips_ += events.slipped;
      if (points_.empty()) state_ = State::kClosedEmpty;
      break;
    }
  }
  return events;
}

}  // namespace vesica::physics
