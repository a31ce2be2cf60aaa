#pragma once
// A registration result as a motion that can be replayed (issue 35): the nodal displacement of a
// tet mesh at a series of times, sampled at any fixed set of material points (the breathing
// patient's liver elements, a tumour centre) at any time: barycentric in the rest mesh, linear in
// time between frames, and periodic over the series so that a recorded breath repeats.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "physics/mesh/barycentric.h"
#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

struct DisplacementFrame {
  double time_s = 0.0;
  Vertices displacement_m;  ///< #V by 3, from the rest mesh
};

class DisplacementSeries {
 public:
  /// Frames ascending in time, each with one row per mesh node, all finite; at least one. The
  /// period of the replay is the span of the times plus the last frame's spacing (one frame:
  /// constant). Throws std::invalid_argument naming the frame.
  DisplacementSeries(TetrahedralMesh rest, std::vector<DisplacementFrame> frames);

  /// Binds material points (at rest, world) to the mesh: those outside it take the nearest tet's
  /// extrapolated weights (LocateInTetMesh). Returns a handle for Sample.
  std::vector<TetLocation> Bind(const std::vector<Eigen::Vector3d>& rest_points_W) const;
  /// Displacements of the bound points at time t (any real t: wrapped into the period).
  std::vector<Eigen::Vector3d> Sample(const std::vector<TetLocation>& points, double t_s) const;
  double period_s() const { return period_s_; }
  const TetrahedralMesh& rest() const { return rest_; }

 private:
  TetrahedralMesh rest_;
  std::vector<DisplacementFrame> frames_;
  double period_s_ = 0.0;
};

/// The series as the motion of fixed material points (rest positions, world): t -> their
/// displacements, the form BreathingPatient::DriveLiver takes (the liver's lattice elements).
std::function<std::vector<Eigen::Vector3d>(double)> MakePointMotion(std::shared_ptr<const DisplacementSeries> series,
                                                                    const std::vector<Eigen::Vector3d>& rest_points_W);

}  // namespace vesica::physics
