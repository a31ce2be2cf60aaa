#include "physics/mesh/barycentric.h"

#include <Eigen/Dense>
#include <limits>

namespace vesica::physics {

Eigen::Vector3d TriangleBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Least-squares solve of p - a = u (b - a) + v (c - a) via the 2x2 normal equations.
  const Eigen::Vector3d e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double det = d00 * d11 - d01 * d01;
  const double v = (d11 * d20 - d01 * d21) / det;
  const double w = (d00 * d21 - d01 * d20) / det;
  return {1.0 - v - w, v, w};
}

TrianglePoint ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Voronoi-region walk (Ericson, Real-Time Collision Detection, 5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, {1, 0, 0}};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, {0, 1, 0}};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, {1 - v, v, 0}};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, {0, 0, 1}};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, {1 - w, 0, w}};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), {0, 1 - w, w}};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {a + ab * v + ac * w, {1 - v - w, v, w}};
}

Eigen::Vector4d TetBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& x0,
                               const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                               const Eigen::Vector3d& x3) {
  Eigen::Matrix3d edges;
  edges << x1 - x0, x2 - x0, x3 - x0;
  const Eigen::Vector3d w = edges.partialPivLu().solve(p - x0);
  return {1.0 - w.sum(), w[0], w[1], w[2]};
}

TetLocation LocateInTetMesh(const TetrahedralMesh& mesh, const Eigen::Vector3d& p) {
  TetLocation best;
  double best_min_weight = -std::numeric_limits<double>::infinity();
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Vector4d w = TetBarycentric(
        p, mesh.vertices.row(mesh.tets(t, 0)).transpose(), mesh.vertices.row(mesh.tets(t, 1)).transpose(),
        mesh.vertices.row(mesh.tets(t, 2)).transpose(), mesh.vertices.row(mesh.tets(t, 3)).transpose());
    const double min_weight = w.minCoeff();
    if (min_weight > best_min_weight) {
      best_min_weight = min_weight;
      best = {t, w};
      if (min_weight >= 0) break;
    }
  }
  return best;
}

Eigen::Vector3d Interpolate(const TetrahedralMesh& mesh, const TetLocation& location) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k)
    x += location.weights[k] * mesh.vertices.row(mesh.tets(location.tet, k)).transpose();
  return x;
}

}  // namespace vesica::physics
