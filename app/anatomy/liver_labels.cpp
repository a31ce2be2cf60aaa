#include "app/anatomy/liver_labels.h"

#include <algorithm>
#include <limits>

namespace vesica::app::anatomy {

namespace {

// Nearest point of the centreline polyline to p.
Eigen::Vector3d NearestCentrelinePoint(const GallbladderCentreline& c, const Eigen::Vector3d& p) {
  Eigen::Vector3d best = c.points_m.front();
  double best_d2 = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < c.points_m.size(); ++i) {
    const Eigen::Vector3d a = c.points_m[i], ab = c.points_m[i + 1] - a;
    const Eigen::Vector3d q = a + std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) * ab;
    if ((p - q).squaredNorm() < best_d2) {
      best_d2 = (p - q).squaredNorm();
      best = q;
    }
  }
  return best;
}

bool OnBedSide(const GallbladderCentreline& c, const LiverLabelRegions& r, const Eigen::Vector3d& p) {
  if (r.bed_side_direction.isZero() && r.bed_height_direction.isZero()) return true;
  const Eigen::Vector3d offset = p - NearestCentrelinePoint(c, p);
  return (r.bed_side_direction.isZero() || offset.dot(r.bed_side_direction) > r.bed_side_min_m) &&
         (r.bed_height_direction.isZero() || offset.dot(r.bed_height_direction) > r.bed_height_min_m);
}

}  // namespace

void LabelLiver(physics::TriangleMesh& mesh, const GallbladderCentreline& gallbladder,
                const LiverLabelRegions& regions) {
  mesh.vertex_labels = Eigen::VectorXi::Constant(mesh.num_vertices(), physics::kLabelNone);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d p = mesh.vertices.row(i);
    const Eigen::Vector3d q = (p - regions.fixed_centre_m).cwiseQuotient(regions.fixed_semi_axes_m);
    if (q.squaredNorm() < 1) mesh.vertex_labels[i] |= physics::kLabelFixed;
    if (GallbladderDistance(gallbladder, p) < regions.bed_distance_m && OnBedSide(gallbladder, regions, p)) {
      mesh.vertex_labels[i] |= physics::kLabelGallbladderBed;
    }
  }
}

}  // namespace vesica::app::anatomy
