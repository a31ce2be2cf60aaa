#include "app/anatomy/surface_distance.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace vesica::app::anatomy {

namespace {

Eigen::Vector3d Corner(const physics::TriangleMesh& m, int f, int k) { return m.vertices.row(m.triangles(f, k)); }

// Moller-Trumbore; returns t of the hit or nothing.
std::optional<double> RayTriangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (std::abs(det) < 1e-18) return std::nullopt;
  const Eigen::Vector3d tv = o - a;
  const double u = tv.dot(pv) / det;
  if (u < 0 || u > 1) return std::nullopt;
  const Eigen::Vector3d qv = tv.cross(e1);
  const double v = d.dot(qv) / det;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = e2.dot(qv) / det;
  if (t < 0) return std::nullopt;
  return t;
}

}  // namespace

Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double DistanceToSurface(const physics::TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    best = std::min(best,
                    (ClosestPointOnTriangle(p, Corner(mesh, f, 0), Corner(mesh, f, 1), Corner(mesh, f, 2)) - p).norm());
  }
  return best;
}

std::optional<double> FirstRayHit(const physics::TriangleMesh& mesh, const Eigen::Vector3d& origin,
                                  const Eigen::Vector3d& direction) {
  std::optional<double> best;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const auto t = RayTriangle(origin, direction, Corner(mesh, f, 0), Corner(mesh, f, 1), Corner(mesh, f, 2));
    if (t && (!best || *t < *best)) best = t;
  }
  return best;
}

bool IsInsideClosedSurface(const physics::TriangleMesh& mesh, const Eigen::Vector3d& p) {
  // A direction unlikely to graze an edge or vertex of a real mesh.
  const Eigen::Vector3d d = Eigen::Vector3d(0.5773, 0.5774, 0.5775).normalized();
  int crossings = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    if (RayTriangle(p, d, Corner(mesh, f, 0), Corner(mesh, f, 1), Corner(mesh, f, 2))) ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace vesica::app::anatomy
