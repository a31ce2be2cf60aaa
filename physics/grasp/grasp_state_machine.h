#pragma once

#include <Eigen/Core>
#include <vector>

#include "physics/collision/surface_ray_caster.h"

namespace vesica::physics {

/// Grasp thresholds (paper §2.5.2). Jaw angles in radians, 0 = closed.
struct GraspSettings {
  double close_angle = 0.05;     ///< rad, jaw at or below this counts as closed
  double open_angle = 0.15;      ///< rad, > close_angle: at or above this counts as open (hysteresis)
  double slip_distance = 10e-3;  ///< m, > 0: a grasped point further than this from the jaw slips
  double friction_limit = 5.0;   ///< N, > 0: constraint force above this makes the point slip
};

/// A grasped surface point, held by barycentric mapping on the touched triangle.
struct GraspPoint {
  int surface = -1;
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
};

/// Per-step inputs, all injected by the scene.
struct GraspInput {
  double jaw_angle = 0.0;                                  ///< rad
  Eigen::Vector3d jaw_position = Eigen::Vector3d::Zero();  ///< m, grasp point between the jaws
  std::vector<SurfaceHit> hits;                            ///< this step's jaw-segment contacts
  /// Current world position (m) and constraint force magnitude (N) of each grasped point,
  /// in the order of points(); ignored unless grasping.
  std::vector<Eigen::Vector3d> grasped_positions;
  std::vector<double> constraint_forces;
};

struct GraspEvents {
  bool grasped = false;   ///< points were taken this step
  bool released = false;  ///< the jaw opened while holding
  int slipped = 0;        ///< points lost to distance or force this step
};

/// Open -> (close while touching) Holding -> (open) Open; Open -> (close in air) ClosedEmpty
/// -> (open) Open. Holding loses points that slip; with none left it is ClosedEmpty: the jaw
/// must open again before a new grasp, as a real grasper must.
class GraspStateMachine {
 public:
  enum class State { kOpen, kHolding, kClosedEmpty };

  /// Throws std::invalid_argument on inconsistent settings.
  explicit GraspStateMachine(const GraspSettings& settings = {});

  /// Advances one step. Throws std::invalid_argument when holding and the grasped position or
  /// force vectors do not match points() in size, or the jaw angle is not finite.
  GraspEvents Update(const GraspInput& input);

  State state() const { return state_; }
  const std::vector<GraspPoint>& points() const { return points_; }
  int total_slips() const { return total_slips_; }

 private:
  GraspSettings settings_;
  State state_ = State::kOpen;
  std::vector<GraspPoint> points_;
  int total_slips_ = 0;
};

}  // namespace vesica::physics
