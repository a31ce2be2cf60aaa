#include "physics/bem/tool_footprint.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>

#include "bem_test_support.h"
#include "physics/bem/bem_errors.h"

namespace vesica::physics {
namespace {

Eigen::VectorXd LumpedAreas(const TriangleMesh& mesh) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int f = 0; f < mesh.num_triangles(); ++f)
    for (int c = 0; c < 3; ++c) a(mesh.triangles(f, c)) += TriangleArea(mesh, f) / 3.0;
  return a;
}

Eigen::Vector3d Centroid(const TriangleMesh& mesh, int f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) c += mesh.vertices.row(mesh.triangles(f, k)).transpose() / 3.0;
  return c;
}

Eigen::Vector3d Normal(const TriangleMesh& mesh, int f) {
  const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0)), b = mesh.vertices.row(mesh.triangles(f, 1)),
                        c = mesh.vertices.row(mesh.triangles(f, 2));
  return (b - a).cross(c - a).normalized();
}

// A uniform traction over whole triangles: int phi_i dA is a third of each covered triangle's
// area at each of its corners (exact for any quadrature that integrates linears), over the total.
TEST(ToolFootprintTest, UniformTractionOnWholeTrianglesLoadsCornersWithAThirdOfTheirArea) {
  const TriangleMesh mesh = testing::LiverLikeEllipsoid(160);
  ToolFootprint footprint;
  footprint.triangles = {3, 4, 17};
  footprint.rho = [](int, const Eigen::Vector3d&) { return 0.0; };
  FootprintOptions options;
  options.shapes = {FootprintShape::kUniform};
  options.subdivision_levels = 1;
  const FootprintModes modes = MakeFootprintModes(mesh, LumpedAreas(mesh), footprint, options);
  std::map<int, double> expected;
  double total = 0;
  for (int f : footprint.triangles) {
    total += TriangleArea(mesh, f);
    for (int c = 0; c < 3; ++c) expected[mesh.triangles(f, c)] += TriangleArea(mesh, f) / 3.0;
  }
  ASSERT_EQ(modes.nodes.size(), expected.size());
  for (std::size_t i = 0; i < modes.nodes.size(); ++i)
    EXPECT_NEAR(modes.load_weights(static_cast<Eigen::Index>(i), 0), expected.at(modes.nodes[i]) / total, 1e-12);
  EXPECT_NEAR(modes.resultant(0), 1.0, 1e-12);
}

// A disc footprint (centred on a triangle's centroid) carries a unit resultant whose centre of
// load is the disc's centre in the tangent plane; a tilt carries none.
TEST(ToolFootprintTest, DiscPunchLoadIsCentredAndTiltsHaveNoResultant) {
  const TriangleMesh mesh = testing::LiverLikeEllipsoid(640);
  const int f = 100;
  const Eigen::Vector3d centre = Centroid(mesh, f), normal = Normal(mesh, f);
  const double radius_m = 0.012;  // several elements across
  FootprintOptions options;
  options.shapes = {FootprintShape::kPunch, FootprintShape::kTiltX, FootprintShape::kUniform};
  const FootprintModes modes =
      MakeFootprintModes(mesh, LumpedAreas(mesh), DiscFootprint(mesh, f, centre, normal, radius_m), options);
  EXPECT_GT(modes.nodes.size(), 10u);
  EXPECT_NEAR(modes.resultant(0), 1.0, 1e-12);
  EXPECT_NEAR(modes.resultant(1), 0.0, 1e-12);
  EXPECT_NEAR(modes.resultant(2), 1.0, 1e-12);
  for (int s : {0, 2}) {
    Eigen::Vector3d load_centre = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < modes.nodes.size(); ++i)
      load_centre +=
          modes.load_weights(static_cast<Eigen::Index>(i), s) * mesh.vertices.row(modes.nodes[i]).transpose();
    const Eigen::Vector3d d = load_centre - centre;
    EXPECT_LT((d - d.dot(normal) * normal).norm(), 0.03 * radius_m) << "shape " << s;
  }
  // The punch weighting puts more of the load toward the rim than the uniform one: on a flat disc
  // the mean distance from the centre is a pi/4 = 0.785 a against 2a/3.
  double punch_r = 0, uniform_r = 0;
  for (std::size_t i = 0; i < modes.nodes.size(); ++i) {
    const double r = (mesh.vertices.row(modes.nodes[i]).transpose() - centre).norm();
    punch_r += modes.load_weights(static_cast<Eigen::Index>(i), 0) * r;
    uniform_r += modes.load_weights(static_cast<Eigen::Index>(i), 2) * r;
  }
  EXPECT_GT(punch_r, uniform_r);
}

// The lumped projection keeps the resultant: sum_j t_j A_j = int p dA = 1.
TEST(ToolFootprintTest, LumpedTractionsKeepTheResultant) {
  const TriangleMesh mesh = testing::LiverLikeEllipsoid(640);
  const Eigen::VectorXd areas = LumpedAreas(mesh);
  FootprintOptions options;
  options.projection = FootprintProjection::kLumped;
  const FootprintModes modes =
      MakeFootprintModes(mesh, areas, DiscFootprint(mesh, 7, Centroid(mesh, 7), Normal(mesh, 7), 0.008), options);
  for (int s = 0; s < 2; ++s) {
    double resultant = 0;
    for (std::size_t i = 0; i < modes.nodes.size(); ++i)
      resultant += modes.traction_per_N(static_cast<Eigen::Index>(i), s) * areas(modes.nodes[i]);
    EXPECT_NEAR(resultant, 1.0, 1e-12);
  }
}

TEST(ToolFootprintTest, BadFootprintsAreRefusedByName) {
  const TriangleMesh mesh = testing::LiverLikeEllipsoid(160);
  const Eigen::VectorXd areas = LumpedAreas(mesh);
  const Eigen::Vector3d c = Centroid(mesh, 0), n = Normal(mesh, 0);
  EXPECT_THROW(DiscFootprint(mesh, -1, c, n, 0.01), BemError);
  EXPECT_THROW(DiscFootprint(mesh, mesh.num_triangles(), c, n, 0.01), BemError);
  EXPECT_THROW(DiscFootprint(mesh, 0, c, n, 0.0), BemError);
  EXPECT_THROW(DiscFootprint(mesh, 0, c, Eigen::Vector3d::Zero(), 0.01), BemError);
  // A disc whose centre lies 0.5 m from the triangle it was given, outside the body, covers nothing.
  const ToolFootprint away = DiscFootprint(mesh, 0, c + 0.5 * n.unitOrthogonal(), n, 0.001);
  try {
    MakeFootprintModes(mesh, areas, away);
    FAIL() << "no throw";
  } catch (const BemError& e) {
    EXPECT_NE(std::string(e.what()).find("covers no part"), std::string::npos) << e.what();
  }
  ToolFootprint outside;
  outside.triangles = {mesh.num_triangles()};
  outside.rho = [](int, const Eigen::Vector3d&) { return 0.0; };
  EXPECT_THROW(MakeFootprintModes(mesh, areas, outside), BemError);
  EXPECT_THROW(MakeFootprintModes(mesh, areas.head(3), DiscFootprint(mesh, 0, c, n, 0.01)), BemError);
  FootprintOptions none;
  none.shapes.clear();
  EXPECT_THROW(MakeFootprintModes(mesh, areas, DiscFootprint(mesh, 0, c, n, 0.01), none), BemError);
}

}  // namespace
}  // namespace vesica::physics
