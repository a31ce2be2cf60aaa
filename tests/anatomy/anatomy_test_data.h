#pragma once
// Loads the committed default anatomy through the mesh_io adapter (validated on load).

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy::testing {

std::filesystem::path AnatomyFile(const std::string& name);  ///< data/anatomy/<name>

physics::TriangleMesh LoadLiver();
physics::TriangleMesh LoadAbdominalWall();
physics::TetrahedralMesh LoadGallbladder(int nodes);      ///< gallbladder_<nodes>.vtu
physics::TriangleMesh LoadGallbladderSurface(int nodes);  ///< gallbladder_<nodes>_surface.vtk

/// Area (m^2) of the triangles whose three vertices all carry `label_bit`.
double LabelledArea(const physics::TriangleMesh& mesh, int label_bit);
/// Mean position of the vertices carrying `label_bit`.
Eigen::Vector3d LabelledCentroid(const physics::TriangleMesh& mesh, int label_bit);

}  // namespace vesica::app::anatomy::testing
