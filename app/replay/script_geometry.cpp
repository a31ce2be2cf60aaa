#include "app/replay/script_geometry.h"

#include <Eigen/Geometry>

namespace vesica::app {

Eigen::Vector3d MoveToward(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double max_step) {
  const Eigen::Vector3d d = to - from;
  const double n = d.norm();
  return n <= max_step ? to : Eigen::Vector3d(from + d * (max_step / n));
}

physics::InstrumentPose PoseFor(const physics::InstrumentMount& mount, const Eigen::Vector3d& tip, double jaw_rad) {
  physics::InstrumentPose p =
      physics::AimAt(mount.p_RemoteCentre_W, tip, (tip - mount.p_RemoteCentre_W).norm(), mount.reference_direction_W);
  p.jaw_angle_rad = jaw_rad;
  return p;
}

physics::Vertices VertexNormals(const physics::TriangleMesh& surface, const physics::Vertices& x) {
  physics::Vertices n = physics::Vertices::Zero(x.rows(), 3);
  for (int f = 0; f < surface.num_triangles(); ++f) {
    const Eigen::Vector3d a = x.row(surface.triangles(f, 0)), b = x.row(surface.triangles(f, 1)),
                          c = x.row(surface.triangles(f, 2));
    const Eigen::Vector3d fn = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) n.row(surface.triangles(f, k)) += fn.transpose();
  }
  n.rowwise().normalize();
  return n;
}

}  // namespace vesica::app
