#pragma once
// Topology queries over triangle and tetrahedral meshes: neighbours, adjacency, boundary extraction.

#include <array>
#include <vector>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// For each vertex, the sorted indices of the vertices sharing an edge with it.
std::vector<std::vector<int>> VertexNeighbours(const TriangleMesh& mesh);
std::vector<std::vector<int>> VertexNeighbours(const TetrahedralMesh& mesh);

/// For each vertex, the indices of the triangles (or tets) that use it.
std::vector<std::vector<int>> IncidentTriangles(const TriangleMesh& mesh);
std::vector<std::vector<int>> IncidentTets(const TetrahedralMesh& mesh);

/// #F by 3: entry (f, k) is the triangle across edge k of f, edge k running from corner k to
/// corner (k+1)%3; -1 on a boundary edge, and -2 on an edge shared by more than two triangles.
Triangles TriangleAdjacency(const TriangleMesh& mesh);

/// The boundary surface of a tetrahedral mesh with its maps back to the volume.
struct TetBoundary {
  TriangleMesh surface;                  ///< outward-oriented, surface-local vertex numbering
  Eigen::VectorXi surface_to_volume;     ///< #surface.V: volume vertex of each surface vertex
  Eigen::VectorXi volume_to_surface;     ///< #volume.V: surface vertex, or -1 for interior ones
  Eigen::VectorXi face_tet;              ///< #surface.F: the tet each boundary face belongs to
  Eigen::VectorXi face_local;            ///< #surface.F: local face 0..3 (opposite that corner)
};

/// Faces used by exactly one tet, oriented outward, with compact surface vertex numbering.
TetBoundary ExtractBoundary(const TetrahedralMesh& mesh);

/// The three corners of local face k of a tet (opposite corner k), ordered so that the face
/// normal points away from corner k for a positively oriented tet.
std::array<int, 3> TetFaceCorners(int k);

}  // namespace vesica::physics
