#pragma once

#include "physics/mesh/mesh_types.h"

namespace vesica::physics {

/// A volumetric tetrahedral mesh (positive signed volume per tet).
struct TetrahedralMesh {
  Vertices vertices;  ///< #V by 3, metres
  Tetrahedra tets;    ///< #T by 4

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_tets() const { return static_cast<int>(tets.rows()); }
};

/// Signed volume of tet t: positive when vertices 1,2,3 are counter-clockwise seen from vertex 0's
/// opposite side, i.e. det[x1-x0, x2-x0, x3-x0] / 6.
double SignedTetVolume(const TetrahedralMesh& mesh, int t);
double SignedTetVolume(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                       const Eigen::Vector3d& x2, const Eigen::Vector3d& x3);
/// Sum of the tets' volumes (m^3).
double TotalVolume(const TetrahedralMesh& mesh);

}  // namespace vesica::physics
