#include "physics/fem/small_strain_stiffness.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <stdexcept>

#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_model.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

const ElasticMaterial kGallbladder{2300.0, 0.45, 1000.0};
constexpr double kSide_m = 0.02;

TetrahedralMesh Cube() { return MakeBoxTetMesh({kSide_m, kSide_m, kSide_m}, {3, 3, 3}); }

// u = A x (+ b) at every node of the given positions, stacked.
Eigen::VectorXd LinearField(const Vertices& x, const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
  Eigen::VectorXd u(3 * x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) u.segment<3>(3 * i) = a * x.row(i).transpose() + b;
  return u;
}

struct Formulation {
  const char* name;
  Eigen::SparseMatrix<double> k;
  Vertices nodes;
};

std::vector<Formulation> AllThree() {
  const TetrahedralMesh cube = Cube();
  const QuadraticTetMesh tet10 = MakeQuadraticTetMesh(cube);
  return {{"linear", LinearTetStiffness(cube, kGallbladder), cube.vertices},
          {"nodal pressure", NodalPressureTetStiffness(cube, kGallbladder), cube.vertices},
          {"quadratic", QuadraticTetStiffness(tet10, kGallbladder), tet10.nodes}};
}

// The shared checklist: symmetric, rigid motions cost nothing, and a constant strain (the patch
// test) stores exactly V (lambda tr(e)^2 + 2 mu e:e) / 2.
TEST(SmallStrainStiffnessTest, SymmetricRigidFreeAndExactForConstantStrain) {
  const double lambda = LameLambda(kGallbladder), mu = LameMu(kGallbladder);
  for (const Formulation& f : AllThree()) {
    SCOPED_TRACE(f.name);
    EXPECT_LT((Eigen::SparseMatrix<double>(f.k.transpose()) - f.k).norm(), 1e-12 * f.k.norm());
    Eigen::Matrix3d spin;
    spin << 0, -0.3, 0.2, 0.3, 0, -0.1, -0.2, 0.1, 0;
    const Eigen::VectorXd rigid = LinearField(f.nodes, spin, Eigen::Vector3d(1e-3, -2e-3, 5e-4));
    const Eigen::VectorXd strain_only =
        LinearField(f.nodes, Eigen::Matrix3d::Identity() * 0.01, Eigen::Vector3d::Zero());
    EXPECT_LT((f.k * rigid).norm(), 1e-10 * f.k.norm() * rigid.norm());
    Eigen::Matrix3d e;
    e << 0.010, 0.002, -0.003, 0.002, -0.004, 0.001, -0.003, 0.001, 0.006;
    const Eigen::VectorXd u = LinearField(f.nodes, e, Eigen::Vector3d::Zero());
    const double volume = kSide_m * kSide_m * kSide_m;
    const double energy = 0.5 * volume * (lambda * e.trace() * e.trace() + 2.0 * mu * e.cwiseProduct(e).sum());
    EXPECT_NEAR(0.5 * u.dot(f.k * u), energy, 1e-10 * energy);
    EXPECT_GT(strain_only.dot(f.k * strain_only), 0.0);
  }
}

// The linear tet's matrix is the trainer's (FemModel's linear stiffness, no fixed nodes).
TEST(SmallStrainStiffnessTest, LinearTetsMatchTheTrainersModel) {
  const TetrahedralMesh cube = Cube();
  FemSettings s;
  s.material = kGallbladder;
  s.element_model = ElementModel::kLinear;
  const FemModel model = BuildFemModel(cube, s, {});
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Eigen::VectorXd x(3 * cube.num_vertices());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = normal(rng);
  Eigen::VectorXd expected;
  SymmetricPatternMultiply(model.pattern, model.linear_stiffness_values, x, expected);
  const Eigen::VectorXd got = LinearTetStiffness(cube, kGallbladder) * x;
  EXPECT_LT((got - expected).norm(), 1e-12 * expected.norm());
}

// The nodal-pressure tet stores at most the linear tet's energy for any displacement (the same
// deviatoric part; a node's mean volumetric strain squared is at most the mean of the squares),
// and less for a bending-like field: that is the locking it removes.
TEST(SmallStrainStiffnessTest, NodalPressureIsNeverStifferThanTheLinearTet) {
  const TetrahedralMesh cube = Cube();
  const Eigen::SparseMatrix<double> linear = LinearTetStiffness(cube, kGallbladder);
  const Eigen::SparseMatrix<double> nodal = NodalPressureTetStiffness(cube, kGallbladder);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd u(3 * cube.num_vertices());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = normal(rng);
    EXPECT_LE(u.dot(nodal * u), u.dot(linear * u) * (1 + 1e-12));
  }
  Eigen::VectorXd bend(3 * cube.num_vertices());  // u_z = x^2 / 2, u_x = -x z: pure bending
  for (int i = 0; i < cube.num_vertices(); ++i) {
    const double px = cube.vertices(i, 0) - 0.5 * kSide_m, pz = cube.vertices(i, 2) - 0.5 * kSide_m;
    bend.segment<3>(3 * i) = Eigen::Vector3d(-px * pz, 0.0, 0.5 * px * px);
  }
  EXPECT_LT(bend.dot(nodal * bend), 0.95 * bend.dot(linear * bend));
}

// 10-node tets hold a quadratic field exactly: u_x = c x^2 / 2 stores
// (lambda + 2 mu) c^2 / 2 * integral of x^2 = (lambda + 2 mu) c^2 L^5 / 6.
TEST(SmallStrainStiffnessTest, QuadraticTetsAreExactForAQuadraticField) {
  const QuadraticTetMesh tet10 = MakeQuadraticTetMesh(Cube());
  const double c = 0.5;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * tet10.num_nodes());
  for (int i = 0; i < tet10.num_nodes(); ++i) u[3 * i] = 0.5 * c * tet10.nodes(i, 0) * tet10.nodes(i, 0);
  const double energy = (LameLambda(kGallbladder) + 2.0 * LameMu(kGallbladder)) * c * c * std::pow(kSide_m, 5) / 6.0;
  EXPECT_NEAR(0.5 * u.dot(QuadraticTetStiffness(tet10, kGallbladder) * u), energy, 1e-10 * energy);
  // Each edge has one midpoint node, shared by its tets, at its middle.
  EXPECT_EQ(tet10.num_corners, Cube().num_vertices());
  const int a = tet10.tets(0, 0), b = tet10.tets(0, 1);
  EXPECT_LT((tet10.nodes.row(tet10.Midpoint(b, a)) - 0.5 * (tet10.nodes.row(a) + tet10.nodes.row(b))).norm(), 1e-15);
}

TEST(SmallStrainStiffnessTest, AnInvertedTetIsRefusedByNumber) {
  TetrahedralMesh cube = Cube();
  std::swap(cube.tets(5, 0), cube.tets(5, 1));
  try {
    LinearTetStiffness(cube, kGallbladder);
    FAIL() << "an inverted tet was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tet 5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesica::physics
