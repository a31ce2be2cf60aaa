#pragma once

#include <Eigen/Core>
#include <vector>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// One connective-tissue spring: a liver surface point and a gallbladder material point,
/// both held by barycentric mapping so they follow their bodies (paper §2.4).
struct TissueSpring {
  int liver_triangle = -1;
  Eigen::Vector3d liver_weights = Eigen::Vector3d::Zero();
  int gallbladder_tet = -1;
  Eigen::Vector4d gallbladder_weights = Eigen::Vector4d::Zero();
  int gallbladder_vertex = -1;  ///< gallbladder (volume) vertex the spring was grown from
  double rest_length = 0.0;     ///< metres
  bool alive = true;            ///< false once cut
};

/// Membrane sheet over the springs for display and burning: points 2s (gallbladder end) and
/// 2s+1 (liver end) of spring s; each triangle belongs to the two springs of its edge.
struct TissueMembrane {
  Triangles triangles;                                             ///< #M by 3, indices into spring end points
  Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> springs;  ///< #M by 2
};

struct ConnectiveTissueSettings {
  Eigen::Vector3d toward_liver = Eigen::Vector3d::Zero();  ///< unit direction to the liver bed
  double offset = 5e-3;  ///< metres, > 0: how far the gallbladder is pushed toward the liver
};

struct ConnectiveTissue {
  std::vector<TissueSpring> springs;
  TissueMembrane membrane;
  int num_alive() const;
};

/// Paper §2.4: offsets each gallbladder surface vertex by `offset` toward the liver; a vertex
/// whose offset path crosses the liver surface gets a spring from it to the crossing (the ray
/// toward the liver), the liver end stored as triangle + weights, the gallbladder end as
/// tetrahedron + weights. A vertex already inside a closed liver (the ray leaves it first) is
/// attached to the face behind it, within `offset`. Membrane triangles join springs whose vertices share a surface
/// edge. Throws std::invalid_argument on a zero direction, non-positive offset or empty meshes.
ConnectiveTissue CreateConnectiveTissue(const TriangleMesh& liver, const TetrahedralMesh& gallbladder,
                                        const ConnectiveTissueSettings& settings);

/// Current positions of a spring's two ends.
Eigen::Vector3d LiverEnd(const TissueSpring& s, const Vertices& liver_vertices, const Triangles& liver_triangles);
Eigen::Vector3d GallbladderEnd(const TissueSpring& s, const Vertices& gallbladder_vertices,
                               const Tetrahedra& gallbladder_tets);

/// Cuts spring `index` (burnt through). Throws std::out_of_range on a bad index.
void CutSpring(ConnectiveTissue& tissue, int index);

}  // namespace vesica::physics
