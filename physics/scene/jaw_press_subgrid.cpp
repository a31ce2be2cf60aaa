#include "physics/scene/jaw_press_subgrid.h"

#include <exception>

namespace vesica::physics {

JawPressSubgrid::JawPressSubgrid(std::shared_ptr<const FemModel> body, std::shared_ptr<const TetBoundary> boundary,
                                 double patch_radius_m, int adopt_steps)
    : body_(std::move(body)),
      boundary_(std::move(boundary)),
      patch_radius_m_(patch_radius_m),
      adopt_steps_(adopt_steps) {}

JawPressSubgrid::~JawPressSubgrid() = default;  // std::async's future waits for its worker

void JawPressSubgrid::AdoptIfDue(long step) {
  if (pending_vertex_ < 0 || step < pending_adopt_step_) return;
  double value = 0.0;
  try {
    value = pending_.get();
  } catch (const std::exception&) {
    value = 0.0;  // no patch here (a bad footprint, a singular patch): the linear footprint's press
  }
  known_[pending_vertex_] = value;
  pending_vertex_ = -1;
}

double JawPressSubgrid::At(int vertex, const RectangularFootprint& jaw, long step) {
  AdoptIfDue(step);
  if (const auto it = known_.find(vertex); it != known_.end()) return it->second;
  if (pending_vertex_ < 0) {
    pending_vertex_ = vertex;
    pending_adopt_step_ = step + adopt_steps_;
    JawSubgridSettings settings;
    settings.patch_radius_m = patch_radius_m_;
    auto work = [body = body_, boundary = boundary_, jaw, settings] {
      return ComputeJawSubgridCompliance(body->rest_mesh, *boundary, body->settings.material, jaw, settings)
          .subgrid_normal_m_per_N;
    };
    pending_ = std::async(adopt_steps_ > 0 ? std::launch::async : std::launch::deferred, work);
    AdoptIfDue(step);
    if (const auto it = known_.find(vertex); it != known_.end()) return it->second;
  }
  return 0.0;
}

}  // namespace vesica::physics
