#include "anatomy_test_data.h"

#include <cmath>

#include "app/anatomy/anatomy_generator.h"
#include "app/mesh_io/mesh_io.h"

namespace vesica::app::anatomy::testing {

std::filesystem::path AnatomyFile(const std::string& name) {
  return std::filesystem::path(VESICA_SOURCE_DIR) / "data" / "anatomy" / name;
}

physics::TriangleMesh LoadLiver() {
  return ReadTriangleMesh(AnatomyFile("liver.vtk"), physics::SurfaceRequirement::kClosed);
}
physics::TriangleMesh LoadAbdominalWall() {
  return ReadTriangleMesh(AnatomyFile("abdominal_wall.vtk"), physics::SurfaceRequirement::kAny);
}
physics::TetrahedralMesh LoadGallbladder(int nodes) {
  return ReadTetrahedralMesh(AnatomyFile(GallbladderStem(nodes) + ".vtu"));
}
physics::TriangleMesh LoadGallbladderSurface(int nodes) {
  return ReadTriangleMesh(AnatomyFile(GallbladderStem(nodes) + "_surface.vtk"), physics::SurfaceRequirement::kClosed);
}

double LabelledArea(const physics::TriangleMesh& mesh, int label_bit) {
  double area = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    bool all = true;
    for (int k = 0; k < 3; ++k) all = all && (mesh.vertex_labels[mesh.triangles(f, k)] & label_bit);
    if (all) area += physics::TriangleArea(mesh, f);
  }
  return area;
}

Eigen::Vector3d LabelledCentroid(const physics::TriangleMesh& mesh, int label_bit) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.vertex_labels[i] & label_bit) {
      sum += mesh.vertices.row(i).transpose();
      ++n;
    }
  }
  return n > 0 ? Eigen::Vector3d(sum / n) : Eigen::Vector3d::Constant(std::nan(""));
}

}  // namespace vesica::app::anatomy::testing
