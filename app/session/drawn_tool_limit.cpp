#include "app/session/drawn_tool_limit.h"

#include <algorithm>

namespace vesica::app {

DrawnToolLimit::DrawnToolLimit(const physics::DissectionModel& model) : model_(model) {
  liver_id_ = caster_.AddSurface(model.liver->rest_surface);
  gallbladder_id_ = caster_.AddSurface(model.gallbladder_boundary.surface);
}

std::array<double, 2> DrawnToolLimit::Update(const std::array<physics::InstrumentPose, 2>& poses,
                                             const physics::Vertices& liver, const physics::Vertices& gallbladder) {
  caster_.UpdateVertices(liver_id_, liver);
  caster_.UpdateVertices(gallbladder_id_, gallbladder);
  std::array<double, 2> drawn{};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& mount = model_.instruments[i];
    drawn[i] = poses[i].insertion_m;
    const Eigen::Vector3d tip = physics::TipPosition(mount.p_RemoteCentre_W, mount.reference_direction_W, poses[i]);
    // The remote centre lies in the abdominal wall, outside every organ: the first crossing
    // enters tissue.
    if (const auto hit = caster_.FirstHit({mount.p_RemoteCentre_W, tip}); hit && !hit->from_inside)
      drawn[i] = std::min(drawn[i], hit->distance);
  }
  return drawn;
}

}  // namespace vesica::app
