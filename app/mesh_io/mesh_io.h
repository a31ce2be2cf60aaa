#pragma once
// Mesh files through VTK's readers and writers, kept out of physics/ so physics stays VTK-free.
// Formats by extension: .vtu .vtk (legacy) .obj .stl .ply. Coordinates in files are metres.
// Triangle-mesh vertex labels travel as the point-data array "vesica_label" (.vtk/.vtu/.ply).
// Every loaded mesh is checked before use: its size first (physics::CheckOrganScale: a file in
// the wrong units is refused before anything is computed on it), then physics validation; errors
// are physics::MeshError naming the file and the element by the file's own numbers, and a file VTK
// cannot parse is refused with VTK's reason. OBJ files are read as geometry only (obj_geometry.h).

#include <filesystem>

#include "physics/mesh/mesh_validation.h"
#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app {

/// Name of the per-vertex integer array carrying physics::VertexLabel bits.
inline constexpr const char* kLabelArrayName = "vesica_label";

physics::TriangleMesh ReadTriangleMesh(const std::filesystem::path& path,
                                       physics::SurfaceRequirement requirement);
/// Reads .vtu or .vtk unstructured grids of tetrahedra (other cell types are an error); the
/// boundary must be a closed manifold surface (physics::ValidateTetMeshBoundary).
physics::TetrahedralMesh ReadTetrahedralMesh(const std::filesystem::path& path);

void WriteTriangleMesh(const physics::TriangleMesh& mesh, const std::filesystem::path& path);
void WriteTetrahedralMesh(const physics::TetrahedralMesh& mesh, const std::filesystem::path& path);

}  // namespace vesica::app
