// TetGen wrapper on an icosphere: positive tets filling the surface, node-count targeting, and
// refusal of impossible requests.
#include "app/anatomy/tet_mesher.h"

#include <gtest/gtest.h>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/mesh_validation.h"
#include "physics/mesh/primitives.h"

namespace vesica::app::anatomy {
namespace {

TEST(TetMesherTest, QualityMeshFillsTheKeptSurface) {
  const physics::TriangleMesh sphere = physics::MakeIcosphere(0.03, 2);  // 162 vertices
  const physics::TetrahedralMesh mesh = Tetrahedralise(sphere, "pq1.4/15YQ");
  EXPECT_NO_THROW(physics::ValidateTetrahedralMesh(mesh, "icosphere"));
  const physics::TetBoundary boundary = physics::ExtractBoundary(mesh);
  EXPECT_EQ(boundary.surface.num_vertices(), sphere.num_vertices()) << "-Y keeps the surface";
  EXPECT_NEAR(physics::TotalVolume(mesh), physics::EnclosedVolume(sphere), 1e-9 * physics::EnclosedVolume(sphere));
}

TEST(TetMesherTest, NodeCountTargetIsReachedWithinFivePercent) {
  const physics::TriangleMesh sphere = physics::MakeIcosphere(0.03, 2);
  const SizedTetMesh sized = TetrahedraliseToNodeCount(sphere, 600, {});
  EXPECT_NEAR(sized.mesh.num_vertices(), 600, 30);
  EXPECT_NE(sized.switches.find("pq1.4/15a"), std::string::npos) << sized.switches;
  const physics::TetQualitySummary q = physics::MeasureTetQuality(sized.mesh);
  EXPECT_GT(q.min_dihedral_deg, 5.0);
  EXPECT_LT(q.max_radius_edge, 2.0);
}

TEST(TetMesherTest, RejectsATargetBelowTheSurfaceCountAndBadSwitches) {
  const physics::TriangleMesh sphere = physics::MakeIcosphere(0.03, 2);
  EXPECT_THROW(TetrahedraliseToNodeCount(sphere, 100, {}), std::invalid_argument);
  physics::TriangleMesh open = sphere;
  open.triangles.conservativeResize(open.num_triangles() - 1, 3);  // a hole: no volume to fill
  EXPECT_ANY_THROW(Tetrahedralise(open, "pq1.4YQ"));
}

}  // namespace
}  // namespace vesica::app::anatomy
