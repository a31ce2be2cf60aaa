#pragma once

#include <string>

#include "physics/mesh/mesh_types.h"

namespace vesica::physics {

/// A surface triangle mesh. Vertex and triangle labels are optional per-element integers
/// (0 when absent) used to mark regions such as the liver's fixed region or gallbladder bed.
struct TriangleMesh {
  Vertices vertices;              ///< #V by 3, metres
  Triangles triangles;            ///< #F by 3
  Eigen::VectorXi vertex_labels;  ///< #V or empty

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_triangles() const { return static_cast<int>(triangles.rows()); }
};

/// Bit flags stored in TriangleMesh::vertex_labels for the anatomy's marked regions.
enum VertexLabel : int {
  kLabelNone = 0,
  kLabelFixed = 1 << 0,            ///< held by ligaments / vena cava: zero displacement
  kLabelGallbladderBed = 1 << 1,   ///< liver surface under the gallbladder
};

/// Area-weighted outward unit normal of triangle f.
Eigen::Vector3d TriangleNormal(const TriangleMesh& mesh, int f);
/// Area of triangle f (m^2).
double TriangleArea(const TriangleMesh& mesh, int f);
/// Enclosed volume by the divergence theorem (positive for a closed, outward-oriented surface).
double EnclosedVolume(const TriangleMesh& mesh);
/// Axis-aligned bounding box as (min, max).
std::pair<Eigen::Vector3d, Eigen::Vector3d> BoundingBox(const Vertices& vertices);

}  // namespace vesica::physics
