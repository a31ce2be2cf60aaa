#pragma once
// Element quality of tetrahedral meshes: the measures TetGen's quality bounds are stated in.

#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

/// Smallest of the six dihedral angles of tet t, in degrees (70.53 for a regular tet).
double MinDihedralAngleDeg(const TetrahedralMesh& mesh, int t);
/// Circumradius over shortest edge of tet t (0.612 for a regular tet; slivers can stay small).
double RadiusEdgeRatio(const TetrahedralMesh& mesh, int t);

struct TetQualitySummary {
  double min_dihedral_deg = 0;    ///< worst (smallest) over the mesh
  double max_dihedral_deg = 0;    ///< worst (largest) over the mesh
  double max_radius_edge = 0;     ///< worst (largest) over the mesh
  double mean_radius_edge = 0;
};
TetQualitySummary MeasureTetQuality(const TetrahedralMesh& mesh);

}  // namespace vesica::physics
