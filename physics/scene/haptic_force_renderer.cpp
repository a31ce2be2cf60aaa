#include "physics/scene/haptic_force_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vesica::physics {

HapticForceRenderer::HapticForceRenderer(double blend_s) : blend_s_(blend_s) {
  if (!(std::isfinite(blend_s) && blend_s > 0))
    throw std::invalid_argument("HapticForceRenderer: blend time must be > 0 s");
}

void HapticForceRenderer::Update(const HapticContactFrame& frame, const Eigen::Vector3d& p_Tool_W, double t_s) {
  const Eigen::Vector3d before = Force(p_Tool_W, t_s);
  frame_ = frame;
  update_s_ = t_s;
  offset_N_ = before - RenderContactForce(frame_, p_Tool_W);
}

Eigen::Vector3d HapticForceRenderer::Force(const Eigen::Vector3d& p_Tool_W, double t_s) const {
  const double fade = std::clamp(1.0 - (t_s - update_s_) / blend_s_, 0.0, 1.0);
  return RenderContactForce(frame_, p_Tool_W) + fade * offset_N_;
}

}  // namespace vesica::physics
