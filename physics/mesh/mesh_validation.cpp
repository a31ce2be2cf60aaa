#include "physics/mesh/mesh_validation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/self_intersection.h"

namespace vesica::physics {

namespace {

/// How a surface's elements are named in messages: by their own numbers, or, for the boundary of
/// a tet mesh, by the volume's vertex numbers and the tet face each triangle is, so that every
/// number in an error is one the file has.
class SurfaceNames {
 public:
  SurfaceNames() = default;
  explicit SurfaceNames(const TetBoundary& boundary) : boundary_(&boundary) {}

  int Vertex(int v) const { return boundary_ ? boundary_->surface_to_volume[v] : v; }
  std::string VertexName(int v) const { return "vertex " + std::to_string(Vertex(v)); }
  std::string TriangleName(int f) const {
    if (!boundary_) return "triangle " + std::to_string(f);
    return "tetrahedron " + std::to_string(boundary_->face_tet[f]) + " face opposite corner " +
           std::to_string(boundary_->face_local[f]);
  }
  std::string Edge(int a, int b) const {
    return "edge (" + std::to_string(Vertex(a)) + ", " + std::to_string(Vertex(b)) + ")";
  }

 private:
  const TetBoundary* boundary_ = nullptr;
};

/// `element` is e.g. "triangle 5"; empty for the mesh as a whole.
[[noreturn]] void Fail(const std::string& source, const std::string& element, const std::string& what) {
  throw MeshError(source + ": " + (element.empty() ? std::string("mesh") : element) + ": " + what);
}

std::string Number(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

void CheckVertices(const Vertices& v, const std::string& source) {
  if (v.rows() == 0) Fail(source, "", "has no vertices");
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    if (!v.row(i).allFinite()) {
      std::ostringstream os;
      os << "non-finite coordinate (" << v(i, 0) << ", " << v(i, 1) << ", " << v(i, 2) << ")";
      Fail(source, "vertex " + std::to_string(i), os.str());
    }
  }
}

template <typename Elements>
void CheckIndices(const Elements& e, int num_vertices, const std::string& source,
                  const std::string& element) {
  if (e.rows() == 0) Fail(source, "", "has no " + element + "s");
  for (Eigen::Index i = 0; i < e.rows(); ++i) {
    const std::string name = element + " " + std::to_string(i);
    for (Eigen::Index k = 0; k < e.cols(); ++k) {
      const int v = e(i, k);
      if (v < 0 || v >= num_vertices)
        Fail(source, name,
             "vertex index " + std::to_string(v) + " out of range [0, " + std::to_string(num_vertices) + ")");
      for (Eigen::Index j = 0; j < k; ++j)
        if (e(i, j) == v) Fail(source, name, "repeats vertex " + std::to_string(v));
    }
  }
}

double MeanEdgeLength(const TriangleMesh& mesh) {
  double sum = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k)
      sum += (mesh.vertices.row(mesh.triangles(f, k)) - mesh.vertices.row(mesh.triangles(f, (k + 1) % 3))).norm();
  return sum / (3.0 * mesh.num_triangles());
}

void CheckDegenerateTriangles(const TriangleMesh& mesh, const std::string& source, const SurfaceNames& names) {
  const double min_area = 1e-12 * std::pow(MeanEdgeLength(mesh), 2);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const double area = TriangleArea(mesh, f);
    if (!(area > min_area)) Fail(source, names.TriangleName(f), "is degenerate (area " + Number(area) + " m^2)");
  }
}

void CheckClosedOrientedManifold(const TriangleMesh& mesh, const std::string& source, const SurfaceNames& names) {
  // Every directed edge must appear once and its reverse once: closed, manifold, consistent.
  std::unordered_map<std::uint64_t, int> directed;
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); };
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k), b = mesh.triangles(f, (k + 1) % 3);
      if (directed.count(key(a, b))) {
        const int other = directed[key(a, b)];
        const bool reversed_too = directed.count(key(b, a)) > 0;
        Fail(source, names.TriangleName(f),
             reversed_too ? names.Edge(a, b) + " is shared by more than two triangles (non-manifold)"
                          : "orientation disagrees with " + names.TriangleName(other) + " across " + names.Edge(a, b));
      }
      directed[key(a, b)] = f;
    }
  }
  for (const auto& [k, f] : directed) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffffu);
    if (!directed.count(key(b, a)))
      Fail(source, names.TriangleName(f), names.Edge(a, b) + " is a boundary edge: surface is open");
  }
  // Vertex-manifold: the triangles around each vertex form one fan (connected through edges).
  const auto incident = IncidentTriangles(mesh);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto& fan = incident[v];
    if (fan.empty()) Fail(source, names.VertexName(v), "is used by no triangle");
    // Walk around v: from a triangle (.., v, next, ..) go to the triangle with edge (next, v).
    std::unordered_map<int, int> next_of;  // outgoing neighbour -> triangle
    for (int f : fan)
      for (int k = 0; k < 3; ++k)
        if (mesh.triangles(f, k) == v) next_of[mesh.triangles(f, (k + 1) % 3)] = f;
    int f = fan.front();
    std::size_t steps = 0;
    do {
      int k = 0;
      while (mesh.triangles(f, k) != v) ++k;
      const int prev = mesh.triangles(f, (k + 2) % 3);  // edge (prev, v) ends at v
      f = next_of.at(prev);
      ++steps;
    } while (f != fan.front() && steps <= fan.size());
    if (steps != fan.size()) Fail(source, names.VertexName(v), "is non-manifold (its triangles form more than one fan)");
  }
}

void CheckNoSelfIntersection(const TriangleMesh& mesh, const std::string& source, const SurfaceNames& names) {
  const auto pairs = SelfIntersections(mesh);
  if (pairs.empty()) return;
  constexpr std::size_t kListed = 10;
  std::string what = "intersects itself: " + std::to_string(pairs.size()) +
                     (pairs.size() == 1 ? " pair of triangles crosses: " : " pairs of triangles cross: ");
  for (std::size_t i = 0; i < std::min(pairs.size(), kListed); ++i)
    what += (i ? "; " : "") + names.TriangleName(pairs[i].first) + " and " + names.TriangleName(pairs[i].second);
  if (pairs.size() > kListed) what += "; and " + std::to_string(pairs.size() - kListed) + " more";
  Fail(source, "", what);
}

void ValidateSurface(const TriangleMesh& mesh, const std::string& source, SurfaceRequirement requirement,
                     const SurfaceNames& names) {
  CheckDegenerateTriangles(mesh, source, names);
  if (requirement != SurfaceRequirement::kClosed) return;
  CheckClosedOrientedManifold(mesh, source, names);
  CheckNoSelfIntersection(mesh, source, names);
  if (EnclosedVolume(mesh) <= 0) Fail(source, "", "normals point inward (enclosed volume is not positive)");
}

}  // namespace

void ValidateTriangleMesh(const TriangleMesh& mesh, const std::string& source,
                          SurfaceRequirement requirement) {
  CheckVertices(mesh.vertices, source);
  CheckIndices(mesh.triangles, mesh.num_vertices(), source, "triangle");
  if (mesh.vertex_labels.size() != 0 && mesh.vertex_labels.size() != mesh.num_vertices())
    Fail(source, "", "has " + std::to_string(mesh.vertex_labels.size()) + " vertex labels for " +
                         std::to_string(mesh.num_vertices()) + " vertices");
  ValidateSurface(mesh, source, requirement, SurfaceNames());
}

void ValidateTetMeshBoundary(const TetrahedralMesh& mesh, const std::string& source) {
  const TetBoundary boundary = ExtractBoundary(mesh);
  if (boundary.surface.num_triangles() == 0) Fail(source, "", "has no boundary faces");
  ValidateSurface(boundary.surface, source, SurfaceRequirement::kClosed, SurfaceNames(boundary));
}

void ValidateTetrahedralMesh(const TetrahedralMesh& mesh, const std::string& source,
                             double min_relative_volume) {
  CheckVertices(mesh.vertices, source);
  CheckIndices(mesh.tets, mesh.num_vertices(), source, "tetrahedron");
  for (int t = 0; t < mesh.num_tets(); ++t) {
    double edge_sum = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        edge_sum += (mesh.vertices.row(mesh.tets(t, i)) - mesh.vertices.row(mesh.tets(t, j))).norm();
    const double scale = std::pow(edge_sum / 6.0, 3);
    const double volume = SignedTetVolume(mesh, t);
    const std::string name = "tetrahedron " + std::to_string(t);
    const std::string volume_text = "(signed volume " + Number(volume) + " m^3)";
    if (std::abs(volume) <= min_relative_volume * scale) Fail(source, name, "is degenerate " + volume_text);
    if (volume < 0) Fail(source, name, "is inverted " + volume_text);
  }
}

}  // namespace vesica::physics
