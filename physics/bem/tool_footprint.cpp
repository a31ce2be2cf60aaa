#include "physics/bem/tool_footprint.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "physics/bem/bem_errors.h"
#include "physics/bem/triangle_quadrature.h"

namespace vesica::physics {
namespace {

// Punch weight 1/sqrt(1 - rho^2), held finite at the edge: a Gauss point never lies on it, but
// one very close would otherwise carry an arbitrary share of the (integrable) singularity.
double PunchWeight(double rho) { return 1.0 / std::sqrt(std::max(1.0 - rho * rho, 1e-3)); }

double ShapeValue(FootprintShape shape, double rho, double xi, double eta) {
  switch (shape) {
    case FootprintShape::kUniform:
      return 1.0;
    case FootprintShape::kPunch:
      return PunchWeight(rho);
    case FootprintShape::kTiltX:
      return xi * PunchWeight(rho);
    case FootprintShape::kTiltY:
      return eta * PunchWeight(rho);
  }
  return 0.0;
}

}  // namespace

ToolFootprint DiscFootprint(const TriangleMesh& surface, int triangle, const Eigen::Vector3d& p_Centre_W,
                            const Eigen::Vector3d& normal_W, double radius_m) {
  if (triangle < 0 || triangle >= surface.num_triangles())
    throw BemError("tool footprint: triangle " + std::to_string(triangle) + " out of range [0, " +
                   std::to_string(surface.num_triangles()) + ")");
  if (!(radius_m > 0) || !std::isfinite(radius_m))
    throw BemError("tool footprint: radius " + std::to_string(radius_m) + " m must be positive and finite");
  if (!p_Centre_W.allFinite() || !(normal_W.norm() > 0)) throw BemError("tool footprint: centre or normal not finite");
  const Eigen::Vector3d n = normal_W.normalized();
  // Triangles whose bounding sphere reaches the disc may hold part of it; of those, only the ones
  // connected to the hit triangle through shared corners count (the disc never jumps to a facing
  // surface across a thin part). One pass over the surface, no adjacency kept.
  const auto reaches = [&](int f) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) centroid += surface.vertices.row(surface.triangles(f, c)).transpose() / 3.0;
    double bound = 0;
    for (int c = 0; c < 3; ++c)
      bound = std::max(bound, (surface.vertices.row(surface.triangles(f, c)).transpose() - centroid).norm());
    return (centroid - p_Centre_W).norm() - bound <= radius_m;
  };
  std::vector<int> candidates;
  for (int f = 0; f < surface.num_triangles(); ++f)
    if (f != triangle && reaches(f)) candidates.push_back(f);
  ToolFootprint footprint;
  footprint.triangles.push_back(triangle);
  std::set<int> reached_vertices;
  for (int c = 0; c < 3; ++c) reached_vertices.insert(surface.triangles(triangle, c));
  for (bool grew = true; grew;) {
    grew = false;
    for (int& f : candidates) {
      if (f < 0) continue;
      bool touches = false;
      for (int c = 0; c < 3; ++c) touches = touches || reached_vertices.count(surface.triangles(f, c)) > 0;
      if (!touches) continue;
      footprint.triangles.push_back(f);
      for (int c = 0; c < 3; ++c) reached_vertices.insert(surface.triangles(f, c));
      f = -1;
      grew = true;
    }
  }
  footprint.centre_W = p_Centre_W;
  footprint.normal_W = n;
  footprint.radius_m = radius_m;
  footprint.rho = [centre = p_Centre_W, n, radius_m](int, const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - centre;
    return (d - d.dot(n) * n).norm() / radius_m;
  };
  return footprint;
}

FootprintModes MakeFootprintModes(const TriangleMesh& surface, const Eigen::VectorXd& lumped_area_m2,
                                  const ToolFootprint& footprint, const FootprintOptions& options) {
  if (lumped_area_m2.size() != surface.num_vertices())
    throw BemError("tool footprint: " + std::to_string(lumped_area_m2.size()) + " lumped areas for " +
                   std::to_string(surface.num_vertices()) + " vertices");
  if (options.shapes.empty()) throw BemError("tool footprint: no traction shapes asked for");
  if (options.subdivision_levels < 0 || options.subdivision_levels > 8)
    throw BemError("tool footprint: subdivision_levels " + std::to_string(options.subdivision_levels) +
                   " outside [0, 8]");
  if (!footprint.rho) throw BemError("tool footprint: no rho function");
  const Eigen::Vector3d n = footprint.normal_W.normalized();
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  const double scale_m = footprint.radius_m > 0 ? footprint.radius_m : 1.0;
  const std::size_t num_shapes = options.shapes.size();

  // Sub-triangles of the unit triangle in barycentric corners: 4^levels of them.
  using Corners = std::array<Eigen::Vector3d, 3>;
  std::vector<Corners> subs{{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()}};
  for (int l = 0; l < options.subdivision_levels; ++l) {
    std::vector<Corners> next;
    next.reserve(4 * subs.size());
    for (const Corners& s : subs) {
      const Eigen::Vector3d m01 = 0.5 * (s[0] + s[1]), m12 = 0.5 * (s[1] + s[2]), m20 = 0.5 * (s[2] + s[0]);
      next.push_back({s[0], m01, m20});
      next.push_back({m01, s[1], m12});
      next.push_back({m20, m12, s[2]});
      next.push_back({m01, m12, m20});
    }
    subs = std::move(next);
  }
  const double sub_fraction = 1.0 / static_cast<double>(subs.size());

  std::map<int, Eigen::VectorXd> loads;  // node -> w per shape
  for (int f : footprint.triangles) {
    if (f < 0 || f >= surface.num_triangles())
      throw BemError("tool footprint: triangle " + std::to_string(f) + " out of range [0, " +
                     std::to_string(surface.num_triangles()) + ")");
    std::array<Eigen::Vector3d, 3> x;
    for (int c = 0; c < 3; ++c)
      x[static_cast<std::size_t>(c)] = surface.vertices.row(surface.triangles(f, c)).transpose();
    const double area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
    // One extra column: the punch weighting, which the tilts are made orthogonal to below.
    Eigen::Matrix<double, 3, Eigen::Dynamic> w =
        Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, static_cast<Eigen::Index>(num_shapes) + 1);
    bool covered = false;
    for (const Corners& s : subs) {
      for (const TriangleQuadraturePoint& q : TriangleGauss7()) {
        const Eigen::Vector3d phi = q.barycentric[0] * s[0] + q.barycentric[1] * s[1] + q.barycentric[2] * s[2];
        const Eigen::Vector3d p = phi[0] * x[0] + phi[1] * x[1] + phi[2] * x[2];
        const double rho = footprint.rho(f, p);
        if (!(rho < 1.0)) continue;
        covered = true;
        const Eigen::Vector3d d = p - footprint.centre_W;
        const double xi = d.dot(e1) / scale_m, eta = d.dot(e2) / scale_m;
        const double weight = q.weight * sub_fraction * area;
        for (std::size_t k = 0; k < num_shapes; ++k)
          w.col(static_cast<Eigen::Index>(k)) += weight * ShapeValue(options.shapes[k], rho, xi, eta) * phi;
        w.col(static_cast<Eigen::Index>(num_shapes)) += weight * PunchWeight(rho) * phi;
      }
    }
    if (!covered) continue;
    for (int c = 0; c < 3; ++c) {
      auto [it, inserted] =
          loads.try_emplace(surface.triangles(f, c), Eigen::VectorXd::Zero(static_cast<Eigen::Index>(num_shapes) + 1));
      it->second += w.row(c).transpose();
    }
  }
  if (loads.empty())
    throw BemError("tool footprint: covers no part of the surface (rho >= 1 on every candidate triangle)");

  FootprintModes modes;
  modes.shapes = options.shapes;
  const Eigen::Index q = static_cast<Eigen::Index>(loads.size());
  Eigen::MatrixXd all(q, static_cast<Eigen::Index>(num_shapes) + 1);
  std::vector<Eigen::Index> local(static_cast<std::size_t>(surface.num_vertices()), -1);
  for (const auto& [node, w] : loads) {
    local[static_cast<std::size_t>(node)] = static_cast<Eigen::Index>(modes.nodes.size());
    all.row(static_cast<Eigen::Index>(modes.nodes.size())) = w.transpose();
    modes.nodes.push_back(node);
  }
  modes.load_weights = all.leftCols(static_cast<Eigen::Index>(num_shapes));
  const Eigen::VectorXd punch = all.rightCols<1>() / all.rightCols<1>().sum();
  // Normalise: unit resultant for uniform and punch, unit integral of |p| for the tilts (the sum
  // of |w| stands in for it), whose resultant is made exactly zero by taking out their punch
  // part (a footprint not symmetric about its centre leaves one).
  modes.resultant.resize(static_cast<Eigen::Index>(num_shapes));
  for (std::size_t k = 0; k < num_shapes; ++k) {
    auto col = modes.load_weights.col(static_cast<Eigen::Index>(k));
    const bool tilt = options.shapes[k] == FootprintShape::kTiltX || options.shapes[k] == FootprintShape::kTiltY;
    if (tilt) col -= col.sum() * punch;
    const double norm = tilt ? col.cwiseAbs().sum() : col.sum();
    if (!(std::abs(norm) > 0)) throw BemError("tool footprint: a traction shape integrates to zero on it");
    col /= norm;
    modes.resultant(static_cast<Eigen::Index>(k)) = col.sum();
  }

  if (options.projection == FootprintProjection::kLumped) {
    modes.traction_per_N = modes.load_weights;
    for (Eigen::Index i = 0; i < q; ++i)
      modes.traction_per_N.row(i) /= lumped_area_m2(modes.nodes[static_cast<std::size_t>(i)]);
    return modes;
  }
  // Consistent traction mass over the loaded nodes' hat functions (all their triangles):
  // int phi_i phi_j dA = area / 12 (1 + [i == j]).
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(q, q);
  for (int f = 0; f < surface.num_triangles(); ++f) {
    std::array<Eigen::Index, 3> idx{-1, -1, -1};
    bool any = false;
    for (int c = 0; c < 3; ++c) {
      idx[static_cast<std::size_t>(c)] = local[static_cast<std::size_t>(surface.triangles(f, c))];
      any = any || idx[static_cast<std::size_t>(c)] >= 0;
    }
    if (!any) continue;
    const double area = TriangleArea(surface, f);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (idx[static_cast<std::size_t>(a)] >= 0 && idx[static_cast<std::size_t>(b)] >= 0)
          mass(idx[static_cast<std::size_t>(a)], idx[static_cast<std::size_t>(b)]) +=
              area / 12.0 * (a == b ? 2.0 : 1.0);
  }
  modes.traction_per_N = mass.llt().solve(modes.load_weights);
  return modes;
}

}  // namespace vesica::physics
