#pragma once
// The device loop's side of haptic rendering (1 kHz, never waits for physics). Between physics
// steps the force follows the latest HapticContactFrame's linear model (its stiffness keeps a
// stiff contact stable); when a new frame arrives, the difference between the old and the new
// model at the tool's current point is faded out over `blend_s` instead of applied at once. The
// per-step compliance that the frame's stiffness comes from includes the tissue's inertia, so it
// over-predicts slow pushes; without the fade every physics step would be a felt click.
// O(1), allocation-free; one instance per instrument, owned by the device thread.

#include <Eigen/Core>

#include "physics/scene/haptic_contact_frame.h"

namespace vesica::physics {

class HapticForceRenderer {
 public:
  /// blend_s > 0: usually the physics step. Throws std::invalid_argument otherwise.
  explicit HapticForceRenderer(double blend_s);

  /// A new physics frame, taken at device time t_s with the tool at p_Tool_W: the rendered force
  /// there and then is unchanged.
  void Update(const HapticContactFrame& frame, const Eigen::Vector3d& p_Tool_W, double t_s);

  /// Force on the tool (N) at device time t_s (>= the last update's) and position p_Tool_W.
  Eigen::Vector3d Force(const Eigen::Vector3d& p_Tool_W, double t_s) const;

 private:
  double blend_s_;
  HapticContactFrame frame_;
  Eigen::Vector3d offset_N_ = Eigen::Vector3d::Zero();  // old model - new model at the update
  double update_s_ = 0;
};

}  // namespace vesica::physics
