#pragma once
// Nearest point of a closed, outward-oriented triangle surface to query points, for contact of
// another body's nodes against it. A uniform grid over the surface's rest triangles (each cell
// lists the triangles whose box, grown by `reach_m`, overlaps it) is built once; queries then
// measure only the few triangles of the query's cell, at the surface's current vertices. The
// surface may deform: a query finds what lies within reach_m of it as long as no vertex has
// moved more than reach_m - max_distance from rest.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

struct SurfaceProximity {
  int triangle = -1;
  Eigen::Vector3d p_Surface_W = Eigen::Vector3d::Zero();  ///< closest point on that triangle
  Eigen::Vector3d normal_W = Eigen::Vector3d::Zero();     ///< the triangle's unit outward normal
  double signed_distance_m = 0;                           ///< negative inside the surface
};

class SurfaceProximityGrid {
 public:
  SurfaceProximityGrid() = default;
  /// `rest`: #V x 3 vertices and #F x 3 outward-wound triangles; reach_m > 0; cell_m > 0.
  /// Throws std::invalid_argument for an empty surface or non-positive sizes.
  SurfaceProximityGrid(const TriangleMesh& rest, double reach_m, double cell_m);

  bool empty() const { return triangles_.rows() == 0; }
  double reach_m() const { return reach_m_; }

  /// Each triangle's bounding sphere and unit normal at the surface's current vertices (#V x 3),
  /// computed once per step and shared by that step's queries (they skip triangles whose sphere
  /// is farther than the best distance found so far).
  struct Frame {
    const Vertices* vertices = nullptr;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> centres, normals;
    Eigen::VectorXd radii;
  };
  Frame MakeFrame(const Vertices& vertices) const;

  /// The surface point nearest to p_W among triangles within reach, with |signed distance| <=
  /// max_distance_m (<= reach_m), or nothing, on the surface as `frame` has it. The sign is that
  /// of (p - closest) . n of the nearest triangle (exact away from edges; at a convex or concave
  /// edge any adjacent triangle gives the same sign).
  std::optional<SurfaceProximity> Nearest(const Eigen::Vector3d& p_W, const Frame& frame, double max_distance_m) const;

 private:
  Triangles triangles_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3i cells_ = Eigen::Vector3i::Zero();
  double cell_m_ = 0, reach_m_ = 0;
  std::vector<int> cell_start_;  // CSR: cell c lists cell_triangles_[cell_start_[c] .. cell_start_[c+1])
  std::vector<int> cell_triangles_;
};

}  // namespace vesica::physics
