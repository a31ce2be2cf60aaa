#include "physics/fem/jaw_footprint.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// A 40 x 20 x 30 mm box (4 x 2 x 3 cells, 10 mm edges: the jaw falls across cell edges and
// diagonals), its top face z = 30 mm, and a 10 x 5 mm jaw on it turned 30 degrees in the face.
TetBoundary Box() { return ExtractBoundary(MakeBoxTetMesh({0.04, 0.02, 0.03}, {4, 2, 3})); }

RectangularFootprint JawOnTop(const Eigen::Vector3d& centre_m, double turn_rad) {
  RectangularFootprint jaw;
  jaw.centre_m = centre_m;
  jaw.normal = Eigen::Vector3d::UnitZ();
  jaw.long_axis = Eigen::Vector3d(std::cos(turn_rad), std::sin(turn_rad), 0.0);
  return jaw;
}

// On a flat face the weights integrate exactly: the area, the centre (sum m0_i x_i is the
// integral of x, since the hats reproduce linear fields), zero first moments about the centre,
// and the second moment sum m_xi_i x_i = long_axis L^3 W / 12.
TEST(JawFootprintTest, WeightsIntegrateTheRectangleExactlyOnAFlatFace) {
  const TetBoundary box = Box();
  const RectangularFootprint jaw = JawOnTop({0.021, 0.0093, 0.03}, std::numbers::pi / 6);
  const FootprintWeights w = ComputeFootprintWeights(box, jaw);
  const double area = jaw.length_m * jaw.width_m;
  EXPECT_NEAR(w.area_m2, area, 1e-15);
  EXPECT_NEAR(w.moments.col(0).sum(), area, 1e-15);
  EXPECT_NEAR(w.moments.col(1).sum(), 0.0, 1e-18);
  EXPECT_NEAR(w.moments.col(2).sum(), 0.0, 1e-18);
  Eigen::Vector3d first = Eigen::Vector3d::Zero(), along = Eigen::Vector3d::Zero(), across = Eigen::Vector3d::Zero();
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.04, 0.02, 0.03}, {4, 2, 3});
  for (size_t i = 0; i < w.nodes.size(); ++i) {
    const Eigen::Vector3d x = mesh.vertices.row(w.nodes[i]).transpose();
    EXPECT_NEAR(x.z(), 0.03, 1e-15) << "only top-face nodes carry weight";
    first += w.moments(static_cast<Eigen::Index>(i), 0) * x;
    along += w.moments(static_cast<Eigen::Index>(i), 1) * x;
    across += w.moments(static_cast<Eigen::Index>(i), 2) * x;
  }
  EXPECT_LT((first / area - jaw.centre_m).norm(), 1e-14);
  const double l = jaw.length_m, wd = jaw.width_m;
  EXPECT_LT((along - jaw.long_axis * l * l * l * wd / 12).norm(), 1e-18);
  EXPECT_LT((across - jaw.normal.cross(jaw.long_axis) * wd * wd * wd * l / 12).norm(), 1e-18);
  EXPECT_GT(w.nodes.size(), 4u);  // the hats of the nodes around the jaw reach into it
}

// The 10-node tets' weights integrate every quadratic field exactly on a flat face (their shape
// functions reproduce it): sum m0_i xi_i^2 = L^3 W / 12, which the linear hats only approximate;
// the area and the centre as before. Near a corner a quadratic weight is negative.
TEST(JawFootprintTest, QuadraticWeightsIntegrateQuadraticFieldsExactlyOnAFlatFace) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.04, 0.02, 0.03}, {4, 2, 3});
  const QuadraticTetMesh tet10 = MakeQuadraticTetMesh(mesh);
  const TetBoundary box = ExtractBoundary(mesh);
  const RectangularFootprint jaw = JawOnTop({0.021, 0.0093, 0.03}, std::numbers::pi / 6);
  const double area = jaw.length_m * jaw.width_m, l = jaw.length_m, wd = jaw.width_m;
  const Eigen::Vector3d across = jaw.normal.cross(jaw.long_axis);
  auto moments = [&](const FootprintWeights& w, const Vertices& x) {
    Eigen::Vector4d sums = Eigen::Vector4d::Zero();  // area, xi^2, eta^2, xi eta
    for (size_t i = 0; i < w.nodes.size(); ++i) {
      const Eigen::Vector3d d = x.row(w.nodes[i]).transpose() - jaw.centre_m;
      const double xi = d.dot(jaw.long_axis), eta = d.dot(across), m0 = w.moments(static_cast<Eigen::Index>(i), 0);
      sums += m0 * Eigen::Vector4d(1.0, xi * xi, eta * eta, xi * eta);
    }
    return sums;
  };
  const FootprintWeights quadratic = ComputeQuadraticFootprintWeights(box, tet10, jaw);
  const Eigen::Vector4d q = moments(quadratic, tet10.nodes);
  EXPECT_NEAR(quadratic.area_m2, area, 1e-15);
  EXPECT_NEAR(q[0], area, 1e-15);
  EXPECT_NEAR(q[1], l * l * l * wd / 12, 1e-18);
  EXPECT_NEAR(q[2], wd * wd * wd * l / 12, 1e-18);
  EXPECT_NEAR(q[3], 0.0, 1e-18);
  const Eigen::Vector4d lin = moments(ComputeFootprintWeights(box, jaw), mesh.vertices);
  EXPECT_GT(std::abs(lin[1] - l * l * l * wd / 12), 1e-3 * l * l * l * wd / 12);  // the hats do not
  EXPECT_LT(quadratic.moments.col(0).minCoeff(), 0.0);
}

// Over the face's edge only the part on the face is under the jaw (the side face is edge-on).
TEST(JawFootprintTest, AJawOverTheFacesEdgeHoldsOnlyTheFace) {
  const FootprintWeights w = ComputeFootprintWeights(Box(), JawOnTop({0.038, 0.01, 0.03}, 0.0));
  EXPECT_NEAR(w.area_m2, 0.007 * 0.005, 1e-15);
}

TEST(JawFootprintTest, BadJawsAreRefusedByName) {
  const TetBoundary box = Box();
  RectangularFootprint jaw = JawOnTop({0.02, 0.01, 0.03}, 0.0);
  jaw.width_m = 0.0;
  EXPECT_THROW(ComputeFootprintWeights(box, jaw), std::invalid_argument);
  jaw = JawOnTop({0.02, 0.01, 0.03}, 0.0);
  jaw.long_axis = Eigen::Vector3d(1, 0, 1).normalized();
  try {
    ComputeFootprintWeights(box, jaw);
    FAIL() << "a long axis not in the jaw's plane was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("perpendicular"), std::string::npos) << e.what();
  }
  jaw = JawOnTop({0.2, 0.01, 0.03}, 0.0);  // beside the body
  EXPECT_THROW(ComputeFootprintWeights(box, jaw), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
