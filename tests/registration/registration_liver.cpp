#include "tests/registration/registration_liver.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "app/anatomy/tet_mesher.h"
#include "app/mesh_io/mesh_io.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/registration/registration_fem_settings.h"
#include "physics/registration/surface_pairing.h"

namespace vesica::test {

using physics::Vertices;

const physics::TetrahedralMesh& RegistrationLiverMesh() {
  static const physics::TetrahedralMesh mesh = [] {
    const physics::TriangleMesh surface = app::ReadTriangleMesh(
        std::string(VESICA_SOURCE_DIR) + "/data/anatomy/liver.vtk", physics::SurfaceRequirement::kClosed);
    // TetrahedraliseToNodeCount(surface, 1294, {2.0, 5}) found this bound: 1,294 nodes, 4,808 tets
    // (the seed's 1,294 / 4,579), in one TetGen run instead of its bisection's twenty.
    return app::anatomy::Tetrahedralise(surface, kRegistrationLiverTetgenSwitches);
  }();
  return mesh;
}

std::shared_ptr<const physics::FemModel> RegistrationLiverModel() {
  static const auto model = std::make_shared<const physics::FemModel>(
      physics::BuildFemModel(RegistrationLiverMesh(), physics::DefaultRegistrationFemSettings("liver"), {}));
  return model;
}

RespiratoryField MakeRespiratoryField(const physics::TetrahedralMesh& mesh) {
  RespiratoryField f;
  f.centre_m = mesh.vertices.colwise().mean().transpose();
  double far = 0.0;
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    const double dx = mesh.vertices(i, 0) - f.centre_m.x();
    if (std::abs(dx) > std::abs(far)) far = dx;
  }
  f.tip_x_m = f.centre_m.x() + far;
  return f;
}

Eigen::Vector3d RespiratoryField::Displacement(const Eigen::Vector3d& X, double phase) const {
  // Rigid part: caudal (the diaphragm pushes the liver down on inspiration), anterior, lateral.
  const Eigen::Vector3d translation(0.002, 0.008, -0.026);
  constexpr double bend_tip = 0.008;
  // Bending: the lobes swing further caudally the farther they are from the centre (quadratic in
  // x, 8 mm at the tip), their cross-sections turning with the slope as in a bent beam (plane
  // sections stay normal to the bent axis), so the bending strains the organ without shearing it.
  const double length = tip_x_m - centre_m.x();
  const double s = (X.x() - centre_m.x()) / length;
  const double bend_z = -bend_tip * s * s;
  const double slope = -2.0 * bend_tip * s / length;  // d bend_z / dx
  const Eigen::Vector3d bend(-(X.z() - centre_m.z()) * slope, 0.0, bend_z);
  return phase * (translation + bend);
}

double BreathingPhase(double time_s) {
  const double s = std::sin(std::numbers::pi * time_s / 4.0);
  return s * s;
}

std::vector<physics::ControlPoint> SampleContour(const physics::TetrahedralMesh& mesh, const Vertices& x,
                                                 int plane_axis, double plane_value, int count, int plane_id,
                                                 double noise_m, unsigned seed) {
  static thread_local std::vector<std::pair<const physics::TetrahedralMesh*, physics::RegistrationSurface>> cache;
  const physics::RegistrationSurface* surface = nullptr;
  for (auto& [m, s] : cache)
    if (m == &mesh) surface = &s;
  if (!surface) {
    cache.emplace_back(&mesh, physics::RegistrationSurface(physics::ExtractBoundary(mesh)));
    surface = &cache.back().second;
  }
  // Segments where the surface crosses the plane, with the in-plane outward normal.
  struct Segment {
    Eigen::Vector3d a, b, outward;
  };
  std::vector<Segment> segments;
  for (Eigen::Index f = 0; f < surface->triangles.rows(); ++f) {
    std::array<Eigen::Vector3d, 3> p;
    for (int k = 0; k < 3; ++k) p[static_cast<size_t>(k)] = x.row(surface->triangles(f, k)).transpose();
    std::vector<Eigen::Vector3d> hits;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& u = p[static_cast<size_t>(k)];
      const Eigen::Vector3d& v = p[static_cast<size_t>((k + 1) % 3)];
      const double du = u[plane_axis] - plane_value, dv = v[plane_axis] - plane_value;
      if ((du < 0.0) != (dv < 0.0)) hits.push_back(u + (v - u) * (du / (du - dv)));
    }
    if (hits.size() != 2) continue;
    Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    n[plane_axis] = 0.0;
    if (n.norm() < 1e-15) continue;
    segments.push_back({hits[0], hits[1], n.normalized()});
  }
  // Chain the segments into loops (shared edge crossings coincide), then place the points evenly
  // by arc length over all loops, as a person outlining the organ would.
  std::vector<Eigen::Vector3d> chain_a, chain_b, chain_normals;
  std::vector<double> chain_length;  // arc length at each chained segment's end
  std::vector<char> used(segments.size(), 0);
  double total = 0.0;
  for (size_t start = 0; start < segments.size(); ++start) {
    if (used[start]) continue;
    used[start] = 1;
    Eigen::Vector3d tail = segments[start].b;
    std::vector<size_t> loop{start};
    for (bool grew = true; grew;) {
      grew = false;
      for (size_t s = 0; s < segments.size(); ++s) {
        if (used[s]) continue;
        if ((segments[s].a - tail).norm() < 1e-9) {
          tail = segments[s].b;
        } else if ((segments[s].b - tail).norm() < 1e-9) {
          std::swap(segments[s].a, segments[s].b);
          tail = segments[s].b;
        } else {
          continue;
        }
        used[s] = 1;
        loop.push_back(s);
        grew = true;
      }
    }
    for (size_t s : loop) {
      chain_a.push_back(segments[s].a);
      chain_b.push_back(segments[s].b);
      chain_normals.push_back(segments[s].outward);
      total += (segments[s].b - segments[s].a).norm();
      chain_length.push_back(total);
    }
  }
  const int axis_u = plane_axis == 0 ? 1 : 0;
  const int axis_v = plane_axis == 2 ? 1 : 2;
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  std::vector<physics::ControlPoint> points;
  size_t s = 0;
  for (int k = 0; k < count && !chain_length.empty(); ++k) {
    const double at = total * (k + 0.5) / count;
    while (s + 1 < chain_length.size() && chain_length[s] < at) ++s;
    const double start = s > 0 ? chain_length[s - 1] : 0.0;
    const double length = chain_length[s] - start;
    physics::ControlPoint point;
    point.p_W = chain_a[s] + (length > 0.0 ? (at - start) / length : 0.0) * (chain_b[s] - chain_a[s]);
    point.inward_normal_W = -chain_normals[s];
    point.p_W[axis_u] += noise(random);
    point.p_W[axis_v] += noise(random);
    point.plane = plane_id;
    points.push_back(point);
  }
  return points;
}

SurfaceError SymmetricSurfaceError(const physics::TetrahedralMesh& mesh, const Vertices& a, const Vertices& b) {
  const physics::TetBoundary boundary = physics::ExtractBoundary(mesh);
  const physics::RegistrationSurface surface(boundary);
  const physics::PairingOptions options{false, 0.0, 1.0};
  SurfaceError e;
  double sum = 0.0;
  int count = 0;
  for (const Vertices* from : {&a, &b}) {
    const Vertices& to = from == &a ? b : a;
    const physics::SurfaceSnapshot snapshot(surface, to);
    for (Eigen::Index s = 0; s < boundary.surface_to_volume.size(); ++s) {
      physics::ControlPoint p;
      p.p_W = from->row(boundary.surface_to_volume[s]).transpose();
      p.inward_normal_W = Eigen::Vector3d::UnitX();
      const auto pairing = physics::PairControlPoint(snapshot, p, options);
      const double d = pairing ? pairing->distance_m : 1.0;
      sum += d;
      e.max_m = std::max(e.max_m, d);
      ++count;
    }
  }
  e.mean_m = sum / count;
  return e;
}

}  // namespace vesica::test
