#pragma once
// Small inline surfaces for the fx tests, with centroids that make the expected values exact.

#include "physics/mesh/triangle_mesh.h"

namespace vesica::fx::testing {

/// A 3 m x 1 m strip in z = 0 of three unit squares, each cut into two triangles:
///   2---3---5---7
///   | \ | \ | \ |      T0 (0,1,2) centroid (1/3, 1/3)   T1 (1,3,2) centroid (2/3, 2/3)
///   0---1---4---6      T2 (1,4,3) centroid (4/3, 1/3)   T3 (4,5,3) centroid (5/3, 2/3)
///                      T4 (4,6,5) centroid (7/3, 1/3)   T5 (6,7,5) centroid (8/3, 2/3)
/// Each triangle has area 0.5 m^2.
inline physics::TriangleMesh MakeStrip() {
  physics::TriangleMesh mesh;
  mesh.vertices.resize(8, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0, 2, 1, 0, 3, 0, 0, 3, 1, 0;
  mesh.triangles.resize(6, 3);
  mesh.triangles << 0, 1, 2, 1, 3, 2, 1, 4, 3, 4, 5, 3, 4, 6, 5, 6, 7, 5;
  return mesh;
}

}  // namespace vesica::fx::testing
