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

// The part of boundary triangle f under the jaw, in the jaw's plane: its projected corners q, the
// clipped polygon (empty when none of it is under the jaw) and the factor from plane areas back to
// the surface's. The hat functions are the barycentric coordinates of the projected triangle (the
// projection of a flat triangle is affine).
struct ClippedTriangle {
  std::array<Point2, 3> q;
  std::vector<Point2> polygon;
  double area_plane = 0;
  double to_surface = 0;

  Eigen::Vector3d Barycentric(const Point2& s) const {
    const double l1 = Cross2(s - q[0], q[2] - q[0]) / (2.0 * area_plane);
    const double l2 = Cross2(q[1] - q[0], s - q[0]) / (2.0 * area_plane);
    return Eigen::Vector3d(1.0 - l1 - l2, l1, l2);
  }
};

ClippedTriangle ClipToJaw(const TetBoundary& boundary, const RectangularFootprint& jaw, int f) {
  const Vertices& x = boundary.surface.vertices;
  const Eigen::Vector3d across = jaw.normal.cross(jaw.long_axis);
  const double half_l = 0.5 * jaw.length_m, half_w = 0.5 * jaw.width_m;
  ClippedTriangle out;
  std::array<Eigen::Vector3d, 3> p;
  for (size_t k = 0; k < 3; ++k) {
    p[k] = x.row(boundary.surface.triangles(f, static_cast<int>(k))).transpose();
    const Eigen::Vector3d d = p[k] - jaw.centre_m;
    out.q[k] = Point2(d.dot(jaw.long_axis), d.dot(across));
  }
  const Eigen::Vector3d centroid = (p[0] + p[1] + p[2]) / 3.0;
  if ((centroid - jaw.centre_m).dot(jaw.normal) <= -jaw.max_depth_m) return out;  // the far side
  const double area_3d = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  out.area_plane = 0.5 * Cross2(out.q[1] - out.q[0], out.q[2] - out.q[0]);
  // Nearly edge-on to the jaw (or facing away): not under it, and its projection is degenerate.
  if (!(out.area_plane > 0.1 * area_3d)) return out;
  std::vector<Point2> polygon(out.q.begin(), out.q.end());
  polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return s.x() - half_l; });
  polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return -half_l - s.x(); });
  polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return s.y() - half_w; });
  polygon = ClipHalfPlane(polygon, [&](const Point2& s) { return -half_w - s.y(); });
  if (polygon.size() >= 3) out.polygon = std::move(polygon);
  out.to_surface = area_3d / out.area_plane;
  return out;
}

FootprintWeights Collect(const std::map<int, Eigen::RowVector3d>& moments, const RectangularFootprint& jaw) {
  FootprintWeights out;
  out.moments.resize(static_cast<Eigen::Index>(moments.size()), 3);
  Eigen::Index row = 0;
  for (const auto& [node, m] : moments) {
    out.nodes.push_back(node);
    out.moments.row(row++) = m;
    out.area_m2 += m[0];
  }
  if (out.nodes.empty())
    throw std::invalid_argument("ComputeFootprintWeights: no surface lies under the jaw (centre " +
                                std::to_string(jaw.centre_m.x()) + ", " + std::to_string(jaw.centre_m.y()) + ", " +
                                std::to_string(jaw.centre_m.z()) + " m)");
  return out;
}

}  // namespace

FootprintWeights ComputeFootprintWeights(const TetBoundary& boundary, const RectangularFootprint& jaw) {
  CheckFootprint(jaw);
  std::map<int, Eigen::RowVector3d> moments;  // by volume node, ordered: a deterministic node order
  for (int f = 0; f < boundary.surface.num_triangles(); ++f) {
    const ClippedTriangle clipped = ClipToJaw(boundary, jaw, f);
    const std::vector<Point2>& polygon = clipped.polygon;
    // phi N_i is quadratic, so the edge-midpoint rule on each fan triangle is exact.
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();  // (corner, moment)
    for (size_t k = 1; k + 1 < polygon.size(); ++k) {
      const std::array<Point2, 3> t{polygon[0], polygon[k], polygon[k + 1]};
      const double a = 0.5 * Cross2(t[1] - t[0], t[2] - t[0]);
      for (size_t e = 0; e < 3; ++e) {
        const Point2 mid = 0.5 * (t[e] + t[(e + 1) % 3]);
        sum += (a / 3.0) * clipped.Barycentric(mid) * Eigen::RowVector3d(1.0, mid.x(), mid.y());
      }
    }
    if (polygon.empty()) continue;
    sum *= clipped.to_surface;
    for (int k = 0; k < 3; ++k) {
      auto [it, added] =
          moments.try_emplace(boundary.surface_to_volume[boundary.surface.triangles(f, k)], Eigen::RowVector3d::Zero());
      it->second += sum.row(k);
    }
  }
  return Collect(moments, jaw);
}

FootprintWeights ComputeQuadraticFootprintWeights(const TetBoundary& boundary, const QuadraticTetMesh& mesh,
                                                  const RectangularFootprint& jaw) {
  CheckFootprint(jaw);
  // Dunavant's 7-point rule (degree 5): the quadratic shape functions times 1, xi, eta are cubic.
  constexpr double kW0 = 0.225, kW1 = 0.132394152788506, kW2 = 0.125939180544827;
  constexpr double kA1 = 0.059715871789770, kB1 = 0.470142064105115, kA2 = 0.797426985353087, kB2 = 0.101286507323456;
  const std::array<std::pair<double, Eigen::Vector3d>, 7> rule{{
      {kW0, {1.0 / 3, 1.0 / 3, 1.0 / 3}},
      {kW1, {kA1, kB1, kB1}},
      {kW1, {kB1, kA1, kB1}},
      {kW1, {kB1, kB1, kA1}},
      {kW2, {kA2, kB2, kB2}},
      {kW2, {kB2, kA2, kB2}},
      {kW2, {kB2, kB2, kA2}},
  }};
  std::map<int, Eigen::RowVector3d> moments;
  for (int f = 0; f < boundary.surface.num_triangles(); ++f) {
    const ClippedTriangle clipped = ClipToJaw(boundary, jaw, f);
    const std::vector<Point2>& polygon = clipped.polygon;
    if (polygon.empty()) continue;
    std::array<int, 6> node;  // the 6-node triangle: corners, then midpoints of edges 01, 12, 20
    for (int k = 0; k < 3; ++k)
      node[static_cast<size_t>(k)] = boundary.surface_to_volume[boundary.surface.triangles(f, k)];
    for (size_t k = 0; k < 3; ++k) node[3 + k] = mesh.Midpoint(node[k], node[(k + 1) % 3]);
    Eigen::Matrix<double, 6, 3> sum = Eigen::Matrix<double, 6, 3>::Zero();
    for (size_t k = 1; k + 1 < polygon.size(); ++k) {
      const std::array<Point2, 3> t{polygon[0], polygon[k], polygon[k + 1]};
      const double a = 0.5 * Cross2(t[1] - t[0], t[2] - t[0]);
      for (const auto& [weight, bary] : rule) {
        const Point2 s = bary[0] * t[0] + bary[1] * t[1] + bary[2] * t[2];
        const Eigen::Vector3d l = clipped.Barycentric(s);
        Eigen::Matrix<double, 6, 1> shape;
        for (int c = 0; c < 3; ++c) shape[c] = l[c] * (2.0 * l[c] - 1.0);
        for (int c = 0; c < 3; ++c) shape[3 + c] = 4.0 * l[c] * l[(c + 1) % 3];
        sum += (weight * a) * shape * Eigen::RowVector3d(1.0, s.x(), s.y());
      }
    }
    sum *= clipped.to_surface;
    for (size_t k = 0; k < 6; ++k) {
      auto [it, added] = moments.try_emplace(node[k], Eigen::RowVector3d::Zero());
      it->second += sum.row(static_cast<Eigen::Index>(k));
    }
  }
  return Collect(moments, jaw);
}

}  // namespace vesica::physics
