#include "physics/mesh/triangle_crossing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace vesica::physics {

namespace {

using Vec = Eigen::Vector3d;
using Tri = std::array<Vec, 3>;

/// Relative margin by which a crossing must pass through (see the header).
constexpr double kMargin = 1e-9;

double LongestEdge(const Tri& a, const Tri& b) {
  double l = 0;
  for (const Tri* t : {&a, &b})
    for (int k = 0; k < 3; ++k) l = std::max(l, ((*t)[k] - (*t)[(k + 1) % 3]).norm());
  return l;
}

/// Barycentric coordinates of x (assumed in the plane) in t, by areas along the normal n.
Vec Barycentric(const Tri& t, const Vec& n, const Vec& x) {
  const double twice_area = n.dot((t[1] - t[0]).cross(t[2] - t[0]));
  return Vec(n.dot((t[1] - x).cross(t[2] - x)), n.dot((t[2] - x).cross(t[0] - x)), n.dot((t[0] - x).cross(t[1] - x))) /
         twice_area;
}

bool StrictlyInside(const Tri& t, const Vec& n, const Vec& x) { return Barycentric(t, n, x).minCoeff() > kMargin; }

/// The segment [p, q] passes through the interior of t (n its unit normal): p and q on strictly
/// opposite sides of the plane and the crossing point strictly inside.
bool SegmentPierces(const Vec& p, const Vec& q, const Tri& t, const Vec& n, double scale) {
  const double dp = n.dot(p - t[0]), dq = n.dot(q - t[0]);
  const double tol = kMargin * scale;
  if (!((dp > tol && dq < -tol) || (dp < -tol && dq > tol))) return false;
  return StrictlyInside(t, n, p + (dp / (dp - dq)) * (q - p));
}

/// All of b's corners lie in a's plane.
bool Coplanar(const Tri& a, const Vec& n_a, const Tri& b, double scale) {
  for (const Vec& v : b)
    if (std::abs(n_a.dot(v - a[0])) > kMargin * scale) return false;
  return true;
}

/// 2D cross product of (u, v) seen along the unit normal n.
double Cross(const Vec& n, const Vec& u, const Vec& v) { return n.dot(u.cross(v)); }

/// Segments [a, b] and [c, d] in the plane of normal n cross at a point strictly inside both.
bool SegmentsCross(const Vec& n, const Vec& a, const Vec& b, const Vec& c, const Vec& d, double scale) {
  const double tol = kMargin * scale * scale;
  const double c_side = Cross(n, b - a, c - a), d_side = Cross(n, b - a, d - a);
  const double a_side = Cross(n, d - c, a - c), b_side = Cross(n, d - c, b - c);
  return ((c_side > tol && d_side < -tol) || (c_side < -tol && d_side > tol)) &&
         ((a_side > tol && b_side < -tol) || (a_side < -tol && b_side > tol));
}

/// Coplanar triangles with no shared vertex: their interiors overlap.
bool CoplanarOverlap(const Tri& a, const Tri& b, const Vec& n, double scale) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (SegmentsCross(n, a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3], scale)) return true;
  // No edges cross: one contains the other (or they are the same triangle), or they are apart.
  const Vec centre_a = (a[0] + a[1] + a[2]) / 3, centre_b = (b[0] + b[1] + b[2]) / 3;
  return StrictlyInside(b, n, centre_a) || StrictlyInside(a, n, centre_b);
}

/// Ray direction r lies strictly inside the wedge spanned by u and v (less than half a turn).
bool InsideWedge(const Vec& n, const Vec& u, const Vec& v, const Vec& r) {
  const double turn = Cross(n, u, v);
  const double tol = kMargin * u.norm() * v.norm();
  if (std::abs(turn) <= tol) return false;
  const double s = turn > 0 ? 1.0 : -1.0;
  return s * Cross(n, u, r) > kMargin * u.norm() * r.norm() && s * Cross(n, r, v) > kMargin * r.norm() * v.norm();
}

bool SameDirection(const Vec& n, const Vec& u, const Vec& r) {
  return std::abs(Cross(n, u, r)) <= kMargin * u.norm() * r.norm() && u.dot(r) > 0;
}

/// a and b share corner 0 only.
bool CrossAtSharedVertex(const Tri& a, const Vec& n_a, const Tri& b, const Vec& n_b, double scale) {
  if (Coplanar(a, n_a, b, scale)) {
    // In one plane both lie in their wedges at the shared corner: they overlap when the wedges do.
    const Vec u = a[1] - a[0], v = a[2] - a[0], r = b[1] - b[0], w = b[2] - b[0];
    if (InsideWedge(n_a, u, v, r) || InsideWedge(n_a, u, v, w) || InsideWedge(n_a, r, w, u) ||
        InsideWedge(n_a, r, w, v))
      return true;
    return (SameDirection(n_a, u, r) && SameDirection(n_a, v, w)) ||
           (SameDirection(n_a, u, w) && SameDirection(n_a, v, r));
  }
  // Otherwise they meet on the line of the two planes, in a segment from the shared corner whose
  // far end is where the edge opposite that corner, in one or the other, passes through.
  return SegmentPierces(a[1], a[2], b, n_b, scale) || SegmentPierces(b[1], b[2], a, n_a, scale);
}

/// a and b share corners 0 and 1: folded when b's third corner lies in a's plane on a's side.
bool FoldedAtSharedEdge(const Tri& a, const Vec& n_a, const Tri& b, double scale) {
  if (!Coplanar(a, n_a, b, scale)) return false;
  const Vec edge = a[1] - a[0];
  return Cross(n_a, edge, a[2] - a[0]) * Cross(n_a, edge, b[2] - a[0]) > 0;
}

bool CrossNoSharedVertex(const Tri& a, const Vec& n_a, const Tri& b, const Vec& n_b, double scale) {
  if (Coplanar(a, n_a, b, scale)) return CoplanarOverlap(a, b, n_a, scale);
  // Non-coplanar triangles meet in a segment whose ends lie on edges: one of the six edges
  // passes through the other triangle.
  for (int k = 0; k < 3; ++k)
    if (SegmentPierces(a[k], a[(k + 1) % 3], b, n_b, scale) || SegmentPierces(b[k], b[(k + 1) % 3], a, n_a, scale))
      return true;
  return false;
}

}  // namespace

bool TrianglesCross(const TriangleMesh& mesh, int f, int g) {
  // Order the corners so that the shared ones come first, in the same order in both.
  std::array<int, 3> ia{}, ib{};
  int shared = 0;
  {
    std::array<int, 3> rest_a{}, rest_b{};
    int na = 0, nb = 0;
    std::array<bool, 3> b_shared{false, false, false};
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.triangles(f, i);
      int j = 0;
      while (j < 3 && mesh.triangles(g, j) != v) ++j;
      if (j < 3) {
        ia[shared] = v;
        ib[shared] = v;
        b_shared[j] = true;
        ++shared;
      } else {
        rest_a[na++] = v;
      }
    }
    for (int j = 0; j < 3; ++j)
      if (!b_shared[j]) rest_b[nb++] = mesh.triangles(g, j);
    for (int k = 0; k < na; ++k) ia[shared + k] = rest_a[k];
    for (int k = 0; k < nb; ++k) ib[shared + k] = rest_b[k];
  }
  if (shared == 3) return true;
  Tri a, b;
  for (int k = 0; k < 3; ++k) {
    a[k] = mesh.vertices.row(ia[k]).transpose();
    b[k] = mesh.vertices.row(ib[k]).transpose();
  }
  const Vec n_a = (a[1] - a[0]).cross(a[2] - a[0]).normalized(), n_b = (b[1] - b[0]).cross(b[2] - b[0]).normalized();
  if (!n_a.allFinite() || !n_b.allFinite()) return false;  // degenerate: ValidateTriangleMesh names those
  const double scale = LongestEdge(a, b);
  switch (shared) {
    case 2:
      return FoldedAtSharedEdge(a, n_a, b, scale);
    case 1:
      return CrossAtSharedVertex(a, n_a, b, n_b, scale);
    default:
      return CrossNoSharedVertex(a, n_a, b, n_b, scale);
  }
}

}  // namespace vesica::physics
