#include "physics/fem/jaw_footprint.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace vesica::physics {

namespace {

using Point2 = Eigen::Vector2d;

double Cross2(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Sutherland-Hodgman: the part of a convex polygon where side(p) <= 0 (side affine).
template <class Side>
std::vector<Point2> ClipHalfPlane(const std::vector<Point2>& polygon, Side side) {
  std::vector<Point2> out;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Point2& p = polygon[k];
    const Point2& q = polygon[(k + 1) % polygon.size()];
    const double sp = side(p), sq = side(q);
    if (sp <= 0.0) out.push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
  return out;
}

void CheckFootprint(const RectangularFootprint& jaw) {
  auto fail = [](const std::string& what) {
    return std::invalid_argument("ComputeFootprintWeights: the jaw's " + what);
  };
  if (!(jaw.length_m > 0.0) || !(jaw.width_m > 0.0) || !std::isfinite(jaw.length_m) || !std::isfinite(jaw.width_m))
    throw fail("length_m and width_m must be positive and finite (got " + std::to_string(jaw.length_m) + ", " +
               std::to_string(jaw.width_m) + ")");
  if (!(jaw.max_depth_m > 0.0) || !std::isfinite(jaw.max_depth_m)) throw fail("max_depth_m must be positive");
  if (!jaw.centre_m.allFinite()) throw fail("centre_m is not finite");
  if (!(std::abs(jaw.normal.norm() - 1.0) < 1e-9) || !(std::abs(jaw.long_axis.norm() - 1.0) < 1e-9))
    throw fail("normal and long_axis must be unit vectors");
  if (!(std::abs(jaw.normal.dot(jaw.long_axis)) < 1e-9)) throw fail("long_axis must be perpendicular to normal");
}

}  // namespace

FootprintWeights ComputeFootprintWeights(const TetBoundary& boundary, const RectangularFootprint& jaw) {
  CheckFootprint(jaw);
  const Vertices& x = boundary.surface.vertices;
  const Eigen::Vector3d across = jaw.normal.cross(jaw.long_axis);
  const double half_l = 0.5 * jaw.length_m, half_w = 0.5 * jaw.width_m;
  auto plane = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - jaw.centre_m;
    return Point2(d.dot(jaw.long_axis), d.dot(across));
  };
  std::map<int, Eigen::RowVector3d> moments;  // by surface vertex, ordered: a deterministic node order
  for (int f = 0; f < boundary.surface.num_triangles(); ++f) {
    std::array<Eigen::Vector3d, 3> p;
    std::array<Point2, 3> q;
    for (int k = 0; k < 3; ++k) {
      p[static_cast<size_t>(k)] = x.row(boundary.surface.triangles(f, k)).transpose();
      q[static_cast<size_t>(k)] = plane(p[static_cast<size_t>(k)]);
    }
    const Eigen::Vector3d centroid = (p[0] + p[1] + p[2]) / 3.0;
    if ((centroid - jaw.centre_m).dot(jaw.normal) <= -jaw.max_depth_m) continue;  // the far side
    const double area_3d = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const double area_plane = 0.5 * Cross2(q[1] - q[0], q[2] - q[0]);
    // Nearly edge-on to the jaw (or facing away): not under it, and its projection is degenerate.
    if (!(area_plane > 0.1 * area_3d)) continue;
    std::vector<Point2> polygon(q.begin(), q.end());
    polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return s.x() - half_l; });
    polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return -half_l - s.x(); });
    polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return s.y() - half_w; });
    polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return -half_w - s.y(); });
    if (polygon.size() < 3) continue;
    // The hat functions are the barycentric coordinates of the projected triangle (the projection
    // of a flat triangle is affine); phi N_i is quadratic, so the edge-midpoint rule on each fan
    // triangle is exact. Areas scale back to the surface by area_3d / area_plane.
    auto hats = [&](const Point2& s) {
      const double l1 = Cross2(s - q[0], q[2] - q[0]) / (2.0 * area_plane);
      const double l2 = Cross2(q[1] - q[0], s - q[0]) / (2.0 * area_plane);
      return Eigen::Vector3d(1.0 - l1 - l2, l1, l2);
    };
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();  // (corner, moment)
    for (size_t k = 1; k + 1 < polygon.size(); ++k) {
      const std::array<Point2, 3> t{polygon[0], polygon[k], polygon[k + 1]};
      const double a = 0.5 * Cross2(t[1] - t[0], t[2] - t[0]);
      for (int e = 0; e < 3; ++e) {
        const Point2 mid = 0.5 * (t[static_cast<size_t>(e)] + t[static_cast<size_t>((e + 1) % 3)]);
        sum += (a / 3.0) * hats(mid) * Eigen::RowVector3d(1.0, mid.x(), mid.y());
      }
    }
    sum *= area_3d / area_plane;
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = moments.try_emplace(boundary.surface.triangles(f, k), Eigen::RowVector3d::Zero());
      it->second += sum.row(k);
    }
  }
  FootprintWeights out;
  out.moments.resize(static_cast<Eigen::Index>(moments.size()), 3);
  Eigen::Index row = 0;
  for (const auto& [vertex, m] : moments) {
    out.nodes.push_back(boundary.surface_to_volume[vertex]);
    out.moments.row(row++) = m;
    out.area_m2 += m[0];
  }
  if (out.nodes.empty())
    throw std::invalid_argument("ComputeFootprintWeights: no surface lies under the jaw (centre " +
                                std::to_string(jaw.centre_m.x()) + ", " + std::to_string(jaw.centre_m.y()) + ", " +
                                std::to_string(jaw.centre_m.z()) + " m)");
  return out;
}

}  // namespace vesica::physics
