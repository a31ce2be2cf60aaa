#pragma once
// The grasper's jaw on the gallbladder while it holds (issue 37): the footprint the jaw's rows
// move (its mean, on the body's rest surface) and the subgrid compliance in series with them
// (physics/fem/jaw_subgrid_compliance.h), which a worker thread computes when the jaws close. It is
// adopted at a fixed step after the grasp (replays stay bit-identical: the step waits for the
// worker only if it is slower) and ramped in, so the jaw's force eases from the linear tets'
// stiffness to the continuum's instead of jumping.

#include <Eigen/Core>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physics/fem/fem_model.h"
#include "physics/fem/jaw_subgrid_compliance.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::physics {

struct GraspJawSettings {
  double length_m = 0.010;  ///< along the shaft, > 0
  double width_m = 0.005;   ///< > 0
  double patch_radius_m = 0.015;
  int adopt_steps = 60;  ///< >= 0; 0: computed within Take
  int ramp_steps = 20;   ///< >= 1
};

/// The closed jaws' rectangle on the body's rest surface at barycentric `weights` of boundary
/// triangle `triangle`: centred there, the triangle's outward normal, the long side along the
/// shaft's direction in that plane (a shaft square to the surface leaves the turn free: any
/// direction in the plane). Empty when the triangle is degenerate or out of range.
std::optional<RectangularFootprint> JawFootprintAt(const TriangleMesh& rest_surface, int triangle,
                                                   const Eigen::Vector3d& weights,
                                                   const Eigen::Vector3d& shaft_direction_W, double length_m,
                                                   double width_m);

class GraspJaw {
 public:
  /// `body`'s rest mesh and `boundary` = its ExtractBoundary (copied).
  GraspJaw(std::shared_ptr<const FemModel> body, const TetBoundary& boundary, const GraspJawSettings& settings);
  ~GraspJaw();  // waits for a worker still running
  GraspJaw(const GraspJaw&) = delete;
  GraspJaw& operator=(const GraspJaw&) = delete;

  /// The jaws close on boundary triangle `triangle` at barycentric `weights` at step `step`: the
  /// footprint is centred there on the rest surface, its normal the triangle's, its long side the
  /// shaft's direction in that plane. Returns false, holding nothing, when no footprint can be
  /// formed (the caller keeps the touched point's rows); true otherwise.
  bool Take(int triangle, const Eigen::Vector3d& weights, const Eigen::Vector3d& shaft_direction_W, long step);
  void Release();
  bool holding() const { return holding_; }

  /// Volume nodes and weights (summing to 1) whose mean the jaw holds.
  const std::vector<int>& nodes() const { return nodes_; }
  const std::vector<double>& weights() const { return weights_; }
  /// The series compliance in force at `step` (m/N, symmetric positive semi-definite): zero before
  /// the adoption step, then ramped to the computed one. At the adoption step it waits for the
  /// worker; a worker that failed (FemError, bad patch) leaves it zero and says why in
  /// failure().
  Eigen::Matrix3d SubgridAt(long step);
  /// The computed compliances, once adopted.
  const std::optional<JawSubgridCompliance>& computed() const { return computed_; }
  const std::string& failure() const { return failure_; }
  /// The boundary it was given, shared (with the press's subgrid workers).
  const std::shared_ptr<const TetBoundary>& boundary() const { return boundary_; }

 private:
  std::shared_ptr<const FemModel> body_;
  std::shared_ptr<const TetBoundary> boundary_;
  GraspJawSettings settings_;
  bool holding_ = false;
  std::vector<int> nodes_;
  std::vector<double> weights_;
  long adopt_step_ = -1;
  std::future<JawSubgridCompliance> pending_;
  std::vector<std::future<JawSubgridCompliance>> abandoned_;  // released before adoption, still running
  std::optional<JawSubgridCompliance> computed_;
  std::string failure_;
};

}  // namespace vesica::physics
