#include "app/anatomy/liver_labels.h"

namespace vesica::app::anatomy {

void LabelLiver(physics::TriangleMesh& mesh, const GallbladderCentreline& gallbladder,
                const LiverLabelRegions& regions) {
  mesh.vertex_labels = Eigen::VectorXi::Constant(mesh.num_vertices(), physics::kLabelNone);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d p = mesh.vertices.row(i);
    const Eigen::Vector3d q = (p - regions.fixed_centre_m).cwiseQuotient(regions.fixed_semi_axes_m);
    if (q.squaredNorm() < 1) mesh.vertex_labels[i] |= physics::kLabelFixed;
    if (GallbladderDistance(gallbladder, p) < regions.bed_distance_m) {
      mesh.vertex_labels[i] |= physics::kLabelGallbladderBed;
    }
  }
}

}  // namespace vesica::app::anatomy
