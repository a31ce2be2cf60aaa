#pragma once
// The surface pipeline of the biopsy paper §3.3 on VTK filters: an implicit shape sampled on a
// voxel volume, (i) marching cubes, (ii) decimation, (iii) smoothing, then cleaning and outward
// orientation. Shapes are fields negative inside, zero on the surface, in the patient frame.

#include <Eigen/Core>
#include <functional>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

/// Scalar field of a shape at a world point p_W (metres): < 0 inside, 0 on the surface, > 0
/// outside. Where it is a signed distance its unit is metres; only its sign and zero set matter.
using ImplicitField = std::function<double(const Eigen::Vector3d& p_W)>;

/// Axis-aligned box in the world frame, metres.
struct Box {
  Eigen::Vector3d min_m;
  Eigen::Vector3d max_m;
};

/// Marching cubes of `field` sampled every `voxel_size_m` over `box` (padded by two voxels so a
/// shape inside the box comes out closed). Keeps the largest connected piece. Dense: use
/// DecimateAndSmooth next.
physics::TriangleMesh ExtractIsosurface(const ImplicitField& field, const Box& box, double voxel_size_m);

struct DecimateSmoothOptions {
  int target_vertices = 1000;     ///< quadric decimation aims at this many vertices (> 3)
  int smoothing_iterations = 20;  ///< windowed-sinc iterations (>= 0)
  double passband = 0.1;          ///< windowed-sinc pass band, (0, 2); smaller smooths more
};

/// Quadric decimation to about `target_vertices`, windowed-sinc smoothing (boundary kept), then
/// clean + triangulate and consistent normals. Orientation is fixed by OrientOutward afterwards.
physics::TriangleMesh DecimateAndSmooth(const physics::TriangleMesh& dense, const DecimateSmoothOptions& options);

/// Keeps the part of the surface on the side of the plane that `normal` points to (the clipped
/// edge becomes the open boundary of the result).
physics::TriangleMesh ClipKeepAbove(const physics::TriangleMesh& mesh, const Eigen::Vector3d& plane_point_m,
                                    const Eigen::Vector3d& normal);

/// Flips every triangle if the normals, on average, point against the field's gradient (the
/// gradient points outward for a negative-inside field). Works for open surfaces too.
void OrientOutward(physics::TriangleMesh& mesh, const ImplicitField& field);

}  // namespace vesica::app::anatomy
