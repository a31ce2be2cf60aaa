#include "physics/tissue/connective_tissue.h"

#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "physics/collision/surface_ray_caster.h"
#include "physics/mesh/barycentric.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::physics {

int ConnectiveTissue::num_alive() const {
  int n = 0;
  for (const auto& s : springs) n += s.alive ? 1 : 0;
  return n;
}

namespace {

// Gallbladder end: a tet containing the vertex, weight 1 on that corner.
std::pair<int, Eigen::Vector4d> VertexInTet(const std::vector<std::vector<int>>& incident, const Tetrahedra& tets,
                                            int v) {
  const int t = incident[v].front();
  Eigen::Vector4d w = Eigen::Vector4d::Zero();
  for (int k = 0; k < 4; ++k)
    if (tets(t, k) == v) w[k] = 1.0;
  return {t, w};
}

}  // namespace

ConnectiveTissue CreateConnectiveTissue(const TriangleMesh& liver, const TetrahedralMesh& gallbladder,
                                        const ConnectiveTissueSettings& settings) {
  const double dir_norm = settings.toward_liver.norm();
  if (!(dir_norm > 0.0) || !settings.toward_liver.allFinite())
    throw std::invalid_argument("CreateConnectiveTissue: settings.toward_liver must be a non-zero direction");
  if (!(settings.offset > 0.0))
    throw std::invalid_argument("CreateConnectiveTissue: settings.offset must be > 0 m, got " +
                                std::to_string(settings.offset));
  if (gallbladder.num_tets() == 0) throw std::invalid_argument("CreateConnectiveTissue: gallbladder has no tetrahedra");
  const Eigen::Vector3d dir = settings.toward_liver / dir_norm;

  SurfaceRayCaster caster;
  const int liver_id = caster.AddSurface(liver);  // checks the liver mesh
  const TetBoundary boundary = ExtractBoundary(gallbladder);
  const auto incident = IncidentTets(gallbladder);

  ConnectiveTissue tissue;
  std::vector<int> spring_of_surface_vertex(boundary.surface.num_vertices(), -1);
  for (int sv = 0; sv < boundary.surface.num_vertices(); ++sv) {
    const int v = boundary.surface_to_volume[sv];
    const Eigen::Vector3d p = gallbladder.vertices.row(v).transpose();
    // The offset vertex collides with the liver iff its offset path crosses the liver surface;
    // the crossing is where the ray toward the liver meets it.
    auto hit = caster.FirstHit(liver_id, {p, p + settings.offset * dir});
    if (!hit) continue;
    // Leaving the liver through its far side means the vertex already lies inside it: attach
    // to the face it entered through, behind it along the same line.
    if (hit->from_inside) {
      hit = caster.FirstHit(liver_id, {p, p - settings.offset * dir});
      if (!hit) continue;  // deeper than the offset: no sensible attachment
    }
    TissueSpring s;
    s.liver_triangle = hit->triangle;
    s.liver_weights = hit->weights;
    std::tie(s.gallbladder_tet, s.gallbladder_weights) = VertexInTet(incident, gallbladder.tets, v);
    s.gallbladder_vertex = v;
    s.rest_length = hit->distance;
    spring_of_surface_vertex[sv] = static_cast<int>(tissue.springs.size());
    tissue.springs.push_back(s);
  }

  // Membrane: a quad (two triangles) between each pair of springs on a shared surface edge.
  std::map<std::pair<int, int>, bool> edges;
  for (int f = 0; f < boundary.surface.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = spring_of_surface_vertex[boundary.surface.triangles(f, k)];
      const int b = spring_of_surface_vertex[boundary.surface.triangles(f, (k + 1) % 3)];
      if (a >= 0 && b >= 0) edges[{std::min(a, b), std::max(a, b)}] = true;
    }
  tissue.membrane.triangles.resize(2 * static_cast<int>(edges.size()), 3);
  tissue.membrane.springs.resize(2 * static_cast<int>(edges.size()), 2);
  int m = 0;
  for (const auto& [e, unused] : edges) {
    const auto [i, j] = e;
    tissue.membrane.triangles.row(m) << 2 * i, 2 * j, 2 * j + 1;
    tissue.membrane.triangles.row(m + 1) << 2 * i, 2 * j + 1, 2 * i + 1;
    tissue.membrane.springs.row(m) << i, j;
    tissue.membrane.springs.row(m + 1) << i, j;
    m += 2;
  }
  return tissue;
}

Eigen::Vector3d LiverEnd(const TissueSpring& s, const Vertices& v, const Triangles& t) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) x += s.liver_weights[k] * v.row(t(s.liver_triangle, k)).transpose();
  return x;
}

Eigen::Vector3d GallbladderEnd(const TissueSpring& s, const Vertices& v, const Tetrahedra& t) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) x += s.gallbladder_weights[k] * v.row(t(s.gallbladder_tet, k)).transpose();
  return x;
}

void CutSpring(ConnectiveTissue& tissue, int index) {
  if (index < 0 || index >= static_cast<int>(tissue.springs.size()))
    throw std::out_of_range("CutSpring: no spring " + std::to_string(index) + " (have " +
                            std::to_string(tissue.springs.size()) + ")");
  tissue.springs[index].alive = false;
}

}  // namespace vesica::physics
