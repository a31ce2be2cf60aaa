#include "physics/registration/rigid_fit.h"

#include <Eigen/Cholesky>

namespace vesica::physics {

Vertices TransformVertices(const Vertices& rest, const Eigen::Isometry3d& transform) {
  Vertices x(rest.rows(), 3);
  for (Eigen::Index i = 0; i < rest.rows(); ++i) x.row(i) = (transform * rest.row(i).transpose()).transpose();
  return x;
}

Eigen::Isometry3d FitRigid(const RegistrationSurface& surface, const Vertices& rest,
                           const std::vector<ControlPoint>& points, const Eigen::Isometry3d& initial,
                           const RigidFitOptions& options) {
  Eigen::Isometry3d transform = initial;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const Vertices x = TransformVertices(rest, transform);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < x.rows(); ++i) centre += x.row(i).transpose();
    centre /= static_cast<double>(x.rows());
    // Small rotation omega about the centre and translation dt: r_i + a_i . [omega; dt] = 0.
    Eigen::Matrix<double, 6, 6> normal = 1e-12 * Eigen::Matrix<double, 6, 6>::Identity();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    int rows = 0;
    for (const ControlPoint& p : points) {
      const auto pairing = PairControlPoint(surface, x, p, options.pairing);
      if (!pairing) continue;
      const Eigen::Vector3d& n = pairing->inward_normal_W;
      const double residual = n.dot(pairing->p_Surface_W - p.p_W);
      Eigen::Matrix<double, 6, 1> a;
      a << (pairing->p_Surface_W - centre).cross(n), n;
      normal += a * a.transpose();
      rhs -= a * residual;
      ++rows;
    }
    if (rows < 6) break;  // too few points to pin six degrees of freedom
    const Eigen::Matrix<double, 6, 1> step = normal.ldlt().solve(rhs);
    const Eigen::Vector3d omega = step.head<3>();
    Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
    if (omega.norm() > 0.0) delta.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix();
    delta.translation() = centre - delta.linear() * centre + step.tail<3>();
    transform = delta * transform;
    if (step.norm() < 1e-10) break;
  }
  return transform;
}

}  // namespace vesica::physics
