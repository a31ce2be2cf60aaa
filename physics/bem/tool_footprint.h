#pragma once
// A tool's contact on the BEM liver as a distributed traction over its physical footprint (issue
// 37) instead of prescribed displacements at the nodes it covers. Nodes prescribed in full make
// the mesh's footprint half an element wider than the tool's (their hat functions carry traction
// outside it), so a coarse mesh is too stiff under a tool by tens of per cent. Here the traction
// p(y) on the footprint comes from a few shapes (traction modes):
//   uniform       p = 1
//   punch         p ~ 1 / sqrt(1 - rho^2)      (a rigid flat punch on a half-space: uniform
//                                              displacement under it; rho = 1 on the edge)
//   tilt x, y     p ~ xi / sqrt(1 - rho^2)     (xi: tangent coordinate, zero resultant)
// each in the three world directions. Its consistent nodal loads w_i = int phi_i p dA are
// integrated over the footprint only (quadrature on subdivided triangles, so an edge inside a
// triangle is resolved), and the traction the BEM takes (nodal values of a linear field) is their
// L2 projection onto the hat functions of the footprint's nodes. The footprint's size no longer
// depends on the mesh, and the number of unknowns (3 per shape) on neither.

#include <Eigen/Core>
#include <functional>
#include <span>
#include <vector>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

enum class FootprintShape { kUniform, kPunch, kTiltX, kTiltY };

/// How the nodal loads become the BEM's nodal tractions.
enum class FootprintProjection {
  kConsistent,  ///< L2 projection: M t = w over the loaded nodes (M: consistent traction mass)
  kLumped,      ///< t_i = w_i / A_i (A_i: a third of the adjacent triangles' area)
};

/// The footprint on a surface: the triangles it may touch and, at any point of them, rho (< 1
/// inside, >= 1 outside: normalised distance from the centre toward the edge).
struct ToolFootprint {
  std::vector<int> triangles;  ///< candidate triangles (those it may cover in part or in full)
  std::function<double(int triangle, const Eigen::Vector3d& p_W)> rho;
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();  ///< unit; the tilts' plane is normal to it
  double radius_m = 0;                                  ///< scale of the tilts' coordinate xi
};

/// A disc of `radius_m` (measured in the tangent plane of `normal_W`) around a point on the
/// surface: the triangles within reach of the point through the surface's adjacency.
ToolFootprint DiscFootprint(const TriangleMesh& surface, int triangle, const Eigen::Vector3d& p_Centre_W,
                            const Eigen::Vector3d& normal_W, double radius_m);

/// Loads and tractions of each traction mode, per newton of mode amplitude. Mode 3 s + c is shape
/// s in world direction c; the uniform and punch shapes have unit resultant, the tilts unit
/// integral of |p|.
struct FootprintModes {
  std::vector<FootprintShape> shapes;
  std::vector<int> nodes;          ///< q loaded nodes (corners of the covered triangles)
  Eigen::MatrixXd load_weights;    ///< q x #shapes: w_i = int phi_i p dA (dimensionless per N)
  Eigen::MatrixXd traction_per_N;  ///< q x #shapes: nodal traction values (1/m^2 per N)
  Eigen::VectorXd resultant;       ///< #shapes: int p dA (1 for uniform and punch, 0 for tilts)
  int num_modes() const { return 3 * static_cast<int>(shapes.size()); }
};

struct FootprintOptions {
  std::vector<FootprintShape> shapes{FootprintShape::kUniform, FootprintShape::kPunch};
  FootprintProjection projection = FootprintProjection::kConsistent;
  int subdivision_levels = 4;  ///< 4^levels sub-triangles per triangle, 7 Gauss points each
};

/// Throws BemError when the footprint covers no part of the surface, lies outside it (a triangle
/// index out of range) or `lumped_area_m2` does not match the surface.
FootprintModes MakeFootprintModes(const TriangleMesh& surface, const Eigen::VectorXd& lumped_area_m2,
                                  const ToolFootprint& footprint, const FootprintOptions& options = {});

}  // namespace vesica::physics
