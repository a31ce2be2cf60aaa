#include "physics/mesh/mesh_validation.h"

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "physics/mesh/mesh_topology.h"

namespace vesica::physics {

namespace {

[[noreturn]] void Fail(const std::string& source, const std::string& element, int index,
                       const std::string& what) {
  std::ostringstream os;
  os << source << ": " << element;
  if (index >= 0) os << ' ' << index;
  os << ": " << what;
  throw MeshError(os.str());
}

void CheckVertices(const Vertices& v, const std::string& source) {
  if (v.rows() == 0) Fail(source, "mesh", -1, "has no vertices");
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    if (!v.row(i).allFinite()) {
      std::ostringstream os;
      os << "non-finite coordinate (" << v(i, 0) << ", " << v(i, 1) << ", " << v(i, 2) << ")";
      Fail(source, "vertex", static_cast<int>(i), os.str());
    }
  }
}

template <typename Elements>
void CheckIndices(const Elements& e, int num_vertices, const std::string& source,
                  const std::string& element) {
  if (e.rows() == 0) Fail(source, "mesh", -1, "has no " + element + "s");
  for (Eigen::Index i = 0; i < e.rows(); ++i) {
    for (Eigen::Index k = 0; k < e.cols(); ++k) {
      const int v = e(i, k);
      if (v < 0 || v >= num_vertices) {
        Fail(source, element, static_cast<int>(i),
             "vertex index " + std::to_string(v) + " out of range [0, " + std::to_string(num_vertices) + ")");
      }
      for (Eigen::Index j = 0; j < k; ++j)
        if (e(i, j) == v) Fail(source, element, static_cast<int>(i), "repeats vertex " + std::to_string(v));
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

void CheckClosedOrientedManifold(const TriangleMesh& mesh, const std::string& source) {
  // Every directed edge must appear once and its reverse once: closed, manifold, consistent.
  std::unordered_map<std::uint64_t, int> directed;
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); };
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k), b = mesh.triangles(f, (k + 1) % 3);
      if (directed.count(key(a, b))) {
        const int other = directed[key(a, b)];
        const bool reversed_too = directed.count(key(b, a)) > 0;
        Fail(source, "triangle", f,
             reversed_too ? "edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                ") is shared by more than two triangles (non-manifold)"
                          : "orientation disagrees with triangle " + std::to_string(other) +
                                " across edge (" + std::to_string(a) + ", " + std::to_string(b) + ")");
      }
      directed[key(a, b)] = f;
    }
  }
  for (const auto& [k, f] : directed) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffffu);
    if (!directed.count(key(b, a)))
      Fail(source, "triangle", f,
           "edge (" + std::to_string(a) + ", " + std::to_string(b) + ") is a boundary edge: surface is open");
  }
  // Vertex-manifold: the triangles around each vertex form one fan (connected through edges).
  const auto incident = IncidentTriangles(mesh);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto& fan = incident[v];
    if (fan.empty()) Fail(source, "vertex", v, "is used by no triangle");
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
    if (steps != fan.size())
      Fail(source, "vertex", v, "is non-manifold (its triangles form more than one fan)");
  }
  if (EnclosedVolume(mesh) <= 0)
    Fail(source, "mesh", -1, "normals point inward (enclosed volume is not positive)");
}

}  // namespace

void ValidateTriangleMesh(const TriangleMesh& mesh, const std::string& source,
                          SurfaceRequirement requirement) {
  CheckVertices(mesh.vertices, source);
  CheckIndices(mesh.triangles, mesh.num_vertices(), source, "triangle");
  if (mesh.vertex_labels.size() != 0 && mesh.vertex_labels.size() != mesh.num_vertices())
    Fail(source, "mesh", -1, "has " + std::to_string(mesh.vertex_labels.size()) + " vertex labels for " +
                                 std::to_string(mesh.num_vertices()) + " vertices");
  const double min_area = 1e-12 * std::pow(MeanEdgeLength(mesh), 2);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const double area = TriangleArea(mesh, f);
    if (!(area > min_area)) Fail(source, "triangle", f, "is degenerate (area " + std::to_string(area) + " m^2)");
  }
  if (requirement == SurfaceRequirement::kClosed) CheckClosedOrientedManifold(mesh, source);
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
    std::ostringstream os;
    os << "(signed volume " << volume << " m^3)";
    if (std::abs(volume) <= min_relative_volume * scale) Fail(source, "tetrahedron", t, "is degenerate " + os.str());
    if (volume < 0) Fail(source, "tetrahedron", t, "is inverted " + os.str());
  }
}

}  // namespace vesica::physics
