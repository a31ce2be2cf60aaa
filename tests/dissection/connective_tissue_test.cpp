#include "physics/tissue/connective_tissue.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/primitives.h"
#include "physics/tissue/spring_forces.h"

namespace vesica::physics {
namespace {

// Liver stand-in: a flat grid at z = 23 mm over x in [-7, 23] mm, y in [-7, 43] mm (off the
// box grid so no ray lands on a triangle edge), i.e. over
// the x <= 20 mm part of the gallbladder box's top face (z = 20 mm).
TriangleMesh LiverPlane() {
  TriangleMesh m;
  const int nx = 4, ny = 6;
  m.vertices.resize(nx * ny, 3);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) m.vertices.row(i + nx * j) << -0.007 + 0.01 * i, -0.007 + 0.01 * j, 0.023;
  m.triangles.resize(2 * (nx - 1) * (ny - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = i + nx * j;
      m.triangles.row(f++) << a, a + nx, a + 1;  // normal -z: faces the gallbladder
      m.triangles.row(f++) << a + 1, a + nx, a + nx + 1;
    }
  return m;
}

TetrahedralMesh GallbladderBox() { return MakeBoxTetMesh({0.04, 0.04, 0.02}, {4, 4, 2}); }

ConnectiveTissue MakeTissue() { return CreateConnectiveTissue(LiverPlane(), GallbladderBox(), {{0, 0, 1}, 5e-3}); }

TEST(ConnectiveTissueTest, SpringsGrowFromTheTopVerticesUnderTheLiver) {
  const TetrahedralMesh gb = GallbladderBox();
  const TriangleMesh liver = LiverPlane();
  const ConnectiveTissue t = MakeTissue();
  ASSERT_EQ(t.springs.size(), 15u);  // x in {0,10,20} mm times y in {0..40} mm, z = 20 mm
  for (const TissueSpring& s : t.springs) {
    const Eigen::Vector3d p = gb.vertices.row(s.gallbladder_vertex).transpose();
    EXPECT_NEAR(p.z(), 0.02, 1e-15);
    EXPECT_LE(p.x(), 0.02 + 1e-15);
    EXPECT_NEAR(s.rest_length, 0.003, 1e-12);
    EXPECT_TRUE(GallbladderEnd(s, gb.vertices, gb.tets).isApprox(p, 1e-15));
    EXPECT_TRUE(LiverEnd(s, liver.vertices, liver.triangles).isApprox(p + Eigen::Vector3d(0, 0, 0.003), 1e-12));
    EXPECT_NEAR(s.liver_weights.sum(), 1.0, 1e-12);
    EXPECT_GE(s.liver_weights.minCoeff(), -1e-12);
  }
}

TEST(ConnectiveTissueTest, VerticesInsideAClosedLiverAttachToTheFaceTheyEntered) {
  // Closed liver slab z in [19, 23] mm: the gallbladder's top vertices (z = 20 mm) are 1 mm in.
  TriangleMesh liver = ExtractBoundary(MakeBoxTetMesh({0.03, 0.05, 0.004}, {3, 5, 1})).surface;
  liver.vertices.rowwise() += Eigen::RowVector3d(-0.007, -0.004, 0.019);
  const TetrahedralMesh gb = GallbladderBox();
  const ConnectiveTissue t = CreateConnectiveTissue(liver, gb, {{0, 0, 1}, 5e-3});
  ASSERT_EQ(t.springs.size(), 15u);
  for (const TissueSpring& s : t.springs) {
    const Eigen::Vector3d p = gb.vertices.row(s.gallbladder_vertex).transpose();
    EXPECT_NEAR(s.rest_length, 0.001, 1e-12);
    EXPECT_NEAR(LiverEnd(s, liver.vertices, liver.triangles).z(), 0.019, 1e-12);
    EXPECT_NEAR(p.z(), 0.02, 1e-15);
  }
}

TEST(ConnectiveTissueTest, MembraneJoinsSpringsOnSharedSurfaceEdges) {
  const TetrahedralMesh gb = GallbladderBox();
  const ConnectiveTissue t = MakeTissue();
  // 3 x 5 grid on the top face: 22 axis edges + 8 cell diagonals, two triangles each.
  ASSERT_EQ(t.membrane.triangles.rows(), 60);
  std::vector<std::set<int>> neighbours(t.springs.size());
  for (int m = 0; m < t.membrane.triangles.rows(); ++m) {
    const int i = t.membrane.springs(m, 0), j = t.membrane.springs(m, 1);
    const double gap =
        (gb.vertices.row(t.springs[i].gallbladder_vertex) - gb.vertices.row(t.springs[j].gallbladder_vertex)).norm();
    EXPECT_LE(gap, 0.01 * std::sqrt(2.0) + 1e-12);
    std::set<int> corners_springs;
    for (int k = 0; k < 3; ++k) corners_springs.insert(t.membrane.triangles(m, k) / 2);
    EXPECT_EQ(corners_springs, (std::set<int>{i, j}));
    neighbours[i].insert(j);
    neighbours[j].insert(i);
  }
  for (size_t s = 0; s < t.springs.size(); ++s) {
    const Eigen::Vector3d p = gb.vertices.row(t.springs[s].gallbladder_vertex).transpose();
    const bool interior = p.x() > 0.005 && p.x() < 0.015 && p.y() > 0.005 && p.y() < 0.035;
    EXPECT_GE(neighbours[s].size(), interior ? 4u : 2u);  // the paper's four neighbours inside
  }
}

TEST(ConnectiveTissueTest, SpringForceIsHookePlusDampingAlongTheSpring) {
  const SpringMaterial mat{200.0, 0.5};
  const Eigen::Vector3d xg(0, 0, 0), xl(0.003, 0.004, 0);  // |d| = 5 mm
  const Eigen::Vector3d vg(0.1, 0, 0), vl(0, 0, 1.0);      // relative v = (-0.1, 0, 1)
  const Eigen::Vector3d u = xl.normalized();
  const Eigen::Vector3d f = SpringForceOnGallbladder(xg, xl, vg, vl, 0.002, mat);
  const double expected = 200.0 * 0.003 + 0.5 * (-0.1 * 0.6);
  EXPECT_TRUE(f.isApprox(expected * u, 1e-14));
  EXPECT_TRUE(SpringForceOnGallbladder(xg, xg, vg, vl, 0.002, mat).isZero());
  EXPECT_TRUE(SpringForceOnGallbladder(xg, xl, vg, vg, 0.005, mat).isZero(1e-15));  // at rest
}

TEST(ConnectiveTissueTest, NodalForcesConserveMomentumAndOpposeOnTheTwoBodies) {
  TetrahedralMesh gb = GallbladderBox();
  const TriangleMesh liver = LiverPlane();
  ConnectiveTissue t = MakeTissue();
  // Pull the gallbladder down 2 mm and give it a velocity: each spring stretches to 5 mm.
  gb.vertices.col(2).array() -= 0.002;
  const Vertices gv = Vertices::Constant(gb.num_vertices(), 3, 0.01);
  const Vertices lv = Vertices::Zero(liver.num_vertices(), 3);
  const SpringMaterial mat{100.0, 0.2};
  auto f = ComputeTissueForces(t, gb, gv, liver, lv, mat);
  const double per_spring = 100.0 * 0.002 + 0.2 * (-0.01);  // relative v along +z is -0.01
  const Eigen::Vector3d total_gb = f.gallbladder.colwise().sum().transpose();
  const Eigen::Vector3d total_liver = f.liver.colwise().sum().transpose();
  EXPECT_TRUE(total_gb.isApprox(Eigen::Vector3d(0, 0, 15 * per_spring), 1e-12));
  EXPECT_TRUE((total_gb + total_liver).isZero(1e-14));
  ASSERT_EQ(f.liver_points.size(), 15u);
  for (const LiverPointForce& p : f.liver_points)
    EXPECT_TRUE(p.force.isApprox(Eigen::Vector3d(0, 0, -per_spring), 1e-12));
  // Each spring's gallbladder end is a node: that node alone carries the spring force.
  EXPECT_NEAR(f.gallbladder(t.springs[0].gallbladder_vertex, 2), per_spring, 1e-14);
  // Cutting removes exactly that spring's share.
  CutSpring(t, 0);
  EXPECT_EQ(t.num_alive(), 14);
  f = ComputeTissueForces(t, gb, gv, liver, lv, mat);
  EXPECT_NEAR(f.gallbladder.col(2).sum(), 14 * per_spring, 1e-12);
  EXPECT_NEAR(f.gallbladder(t.springs[0].gallbladder_vertex, 2), 0.0, 1e-15);
}

TEST(ConnectiveTissueTest, RejectsBadInput) {
  EXPECT_THROW(CreateConnectiveTissue(LiverPlane(), GallbladderBox(), {{0, 0, 0}, 5e-3}), std::invalid_argument);
  EXPECT_THROW(CreateConnectiveTissue(LiverPlane(), GallbladderBox(), {{0, 0, 1}, -1.0}), std::invalid_argument);
  ConnectiveTissue t = MakeTissue();
  EXPECT_THROW(CutSpring(t, 15), std::out_of_range);
  const TetrahedralMesh gb = GallbladderBox();
  const TriangleMesh liver = LiverPlane();
  EXPECT_THROW(ComputeTissueForces(t, gb, Vertices::Zero(2, 3), liver, Vertices::Zero(liver.num_vertices(), 3), {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
