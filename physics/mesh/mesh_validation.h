#pragma once
// Checks a mesh at the door: every defect is reported with the mesh's source name and the
// offending element, e.g. "data/liver.vtk: tetrahedron 17: inverted (signed volume -2.1e-09 m^3)".

#include <stdexcept>
#include <string>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// A mesh that cannot be used. what() names the source and the element.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class SurfaceRequirement {
  kAny,     ///< finite coordinates, valid indices, no degenerate triangles
  kClosed,  ///< also edge-manifold, vertex-manifold, closed, not self-intersecting, consistently and
            ///< outwardly oriented
};

/// Throws MeshError at the first defect; `source` names the mesh in the message (a file path).
void ValidateTriangleMesh(const TriangleMesh& mesh, const std::string& source,
                          SurfaceRequirement requirement);

/// The boundary of a (valid) tet mesh must be a closed, manifold, outward surface (kClosed);
/// errors name the mesh's own numbers: "vertex 26" is the volume's vertex 26, a face is named
/// "tetrahedron 5 face opposite corner 2". Call after ValidateTetrahedralMesh.
void ValidateTetMeshBoundary(const TetrahedralMesh& mesh, const std::string& source);

/// Throws MeshError for non-finite coordinates, out-of-range or repeated indices, and degenerate
/// or inverted tets (|signed volume| below `min_relative_volume` times the mean edge length cubed).
void ValidateTetrahedralMesh(const TetrahedralMesh& mesh, const std::string& source,
                             double min_relative_volume = 1e-9);

}  // namespace vesica::physics
