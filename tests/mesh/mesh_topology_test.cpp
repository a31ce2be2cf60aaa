#include "physics/mesh/mesh_topology.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

TEST(MeshTopologyTest, BoxBoundaryHasExpectedCountsAndOrientation) {
  const auto box = MakeBoxTetMesh({2.0, 1.0, 1.0}, {4, 2, 3});
  EXPECT_EQ(box.num_vertices(), 5 * 3 * 4);
  EXPECT_EQ(box.num_tets(), 6 * 4 * 2 * 3);
  EXPECT_NEAR(TotalVolume(box), 2.0, 1e-12);

  const auto b = ExtractBoundary(box);
  // Each boundary quad is split into 2 triangles: 2 * (xy + yz + zx faces) * 2 sides.
  EXPECT_EQ(b.surface.num_triangles(), 2 * 2 * (4 * 2 + 2 * 3 + 3 * 4));
  // Surface vertices: all minus the interior (3 * 1 * 2).
  EXPECT_EQ(b.surface.num_vertices(), 60 - 3 * 1 * 2);
  EXPECT_NEAR(EnclosedVolume(b.surface), 2.0, 1e-12);  // outward orientation, closed
  for (int s = 0; s < b.surface.num_vertices(); ++s) {
    EXPECT_EQ(b.volume_to_surface[b.surface_to_volume[s]], s);
    EXPECT_EQ(b.surface.vertices.row(s), box.vertices.row(b.surface_to_volume[s]));
  }
  // Each face's corners are corners of its tet.
  for (int f = 0; f < b.surface.num_triangles(); ++f)
    for (int i = 0; i < 3; ++i) {
      const int v = b.surface_to_volume[b.surface.triangles(f, i)];
      EXPECT_TRUE((box.tets.row(b.face_tet[f]).array() == v).any());
      EXPECT_NE(box.tets(b.face_tet[f], b.face_local[f]), v);
    }
}

TEST(MeshTopologyTest, IcosphereIsClosedWithEulerCharacteristicTwo) {
  const auto sphere = MakeIcosphere(1.0, 2);
  EXPECT_EQ(sphere.num_vertices(), 162);
  const auto adjacency = TriangleAdjacency(sphere);
  EXPECT_TRUE((adjacency.array() >= 0).all());
  // Adjacency is symmetric.
  for (int f = 0; f < sphere.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE((adjacency.row(adjacency(f, k)).array() == f).any());
  const auto n = VertexNeighbours(sphere);
  std::size_t edges2 = 0;
  for (const auto& l : n) edges2 += l.size();
  const long V = sphere.num_vertices(), E = static_cast<long>(edges2 / 2), F = sphere.num_triangles();
  EXPECT_EQ(V - E + F, 2);
  // Icosahedron corners have 5 neighbours, all others 6.
  for (int v = 0; v < V; ++v) EXPECT_EQ(n[v].size(), v < 12 ? 5u : 6u) << "vertex " << v;
  EXPECT_GT(EnclosedVolume(sphere), 0.0);
  EXPECT_NEAR(EnclosedVolume(MakeIcosphere(1.0, 4)), 4.0 / 3.0 * std::numbers::pi, 0.01);
}

TEST(MeshTopologyTest, OpenStripHasBoundaryEdgesAndNonManifoldIsFlagged) {
  TriangleMesh m;
  m.vertices.resize(5, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1;
  m.triangles.resize(3, 3);
  m.triangles << 0, 1, 2, 1, 3, 2, 1, 2, 4;  // edge (1,2) used three times
  const auto a = TriangleAdjacency(m);
  EXPECT_EQ(a(0, 1), -2);
  EXPECT_EQ(a(0, 0), -1);
  EXPECT_EQ(a(0, 2), -1);
}

TEST(MeshTopologyTest, TetNeighboursAndIncidence) {
  const auto box = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  const auto n = VertexNeighbours(box);
  // The diagonal corners 0 and 7 are shared by all six tets: connected to all other corners.
  EXPECT_EQ(n[0].size(), 7u);
  EXPECT_EQ(n[7].size(), 7u);
  EXPECT_EQ(IncidentTets(box)[0].size(), 6u);
}

}  // namespace
}  // namespace vesica::physics
