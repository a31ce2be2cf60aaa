#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// A tool segment (shaft, jaw, hook) from a to b, world frame, metres.
struct ToolSegment {
  Eigen::Vector3d a;
  Eigen::Vector3d b;
};

/// First crossing of a segment with an organ surface (paper §2.5.1).
struct SurfaceHit {
  int surface = -1;                                   ///< id returned by AddSurface
  int triangle = -1;                                  ///< row of the surface's triangles
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  ///< barycentric on the triangle
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< world, metres
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   ///< unit geometric normal (winding order)
  double distance = 0.0;                              ///< from a along the segment, metres
  bool from_inside = false;                           ///< the segment crossed the triangle against its normal
};

/// Ray-based collision of tool segments against deforming triangle surfaces. Each surface
/// keeps a Bullet BVH over its triangles; UpdateVertices refits it (topology is fixed).
/// Bullet stays behind the pimpl; the exact hit is computed in double precision.
class SurfaceRayCaster {
 public:
  SurfaceRayCaster();
  ~SurfaceRayCaster();
  SurfaceRayCaster(const SurfaceRayCaster&) = delete;
  SurfaceRayCaster& operator=(const SurfaceRayCaster&) = delete;

  /// Registers a surface; returns its id. Throws std::invalid_argument on empty or
  /// out-of-range triangles or non-finite vertices.
  int AddSurface(const TriangleMesh& surface);

  /// New positions (#V by 3) for surface `id`; refits the BVH. Throws on wrong size or id.
  void UpdateVertices(int id, const Vertices& vertices);

  /// Nearest crossing along the segment over all surfaces, or nothing.
  std::optional<SurfaceHit> FirstHit(const ToolSegment& segment) const;

  /// Nearest crossing with one surface.
  std::optional<SurfaceHit> FirstHit(int id, const ToolSegment& segment) const;

  int num_surfaces() const;

 private:
  struct Surface;
  std::vector<std::unique_ptr<Surface>> surfaces_;
};

}  // namespace vesica::physics
