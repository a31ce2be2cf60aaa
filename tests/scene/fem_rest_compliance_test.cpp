// The constraint compliance of the gallbladder at rest: its columns against the FEM body's own
// step compliance (an independent CHOLMOD path: exact for a linear body), and the background
// refactorisation that keeps spring cuts out of the physics step.

#include "physics/scene/fem_rest_compliance.h"

#include <gtest/gtest.h>

#include <future>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "physics/fem/fem_body.h"
#include "physics/fem/fem_error.h"
#include "physics/fem/fem_model.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

class FemRestComplianceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    mesh_ = MakeBoxTetMesh(Eigen::Vector3d(0.04, 0.02, 0.02), Eigen::Vector3i(6, 3, 3));
    const TetrahedralMesh& mesh = mesh_;
    FemSettings s;
    s.body_name = "test gallbladder";
    s.material.youngs_modulus_Pa = 2300.0;
    s.material.poisson_ratio = 0.45;
    s.material.density_kg_per_m3 = 1000.0;
    s.element_model = ElementModel::kLinear;
    s.solver = LinearSolverKind::kCholmod;
    s.time_step_s = 0.005;
    s.rayleigh_mass_per_s = 0.1;
    s.rayleigh_stiffness_s = 0.01;
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (mesh.vertices(v, 0) < 1e-9) fixed_.push_back({v, {true, true, true}});
    model_ = std::make_shared<const FemModel>(BuildFemModel(mesh, s, fixed_));
    // Springs on the far half of the top face, as the connective tissue holds the gallbladder.
    k_.setZero(model_->num_dofs());
    c_.setZero(model_->num_dofs());
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (mesh.vertices(v, 2) > 0.02 - 1e-9 && mesh.vertices(v, 0) > 0.02) {
        k_.segment<3>(3 * v).setConstant(20.0);
        c_.segment<3>(3 * v).setConstant(0.05);
      }
    node_ = mesh.num_vertices() - 1;  // a free corner
  }

  // The FEM body's compliance for a unit force at `node` (its first step's system matrix).
  Eigen::MatrixXd BodyColumns(const Eigen::VectorXd& k, const Eigen::VectorXd& c, int node) const {
    FemBody body(model_);
    body.SetAttachmentStiffness(k, c);
    body.Step();  // at rest with no load: stays at rest, assembles S
    TetLocation at;
    for (int t = 0; t < model_->rest_mesh.num_tets() && at.tet < 0; ++t)
      for (int corner = 0; corner < 4; ++corner)
        if (model_->rest_mesh.tets(t, corner) == node) {
          at.tet = t;
          at.weights[corner] = 1.0;
        }
    return body.Compliance({at}).response;
  }

  TetrahedralMesh mesh_;
  std::vector<DirichletNode> fixed_;
  std::shared_ptr<const FemModel> model_;
  Eigen::VectorXd k_, c_;
  int node_ = -1;
};

TEST_F(FemRestComplianceTest, ColumnsAreTheLinearBodysStepCompliance) {
  FemRestCompliance compliance(model_);
  compliance.SetAttachments(k_, c_);
  const Eigen::MatrixXd expected = BodyColumns(k_, c_, node_);
  const Eigen::MatrixXd columns = compliance.NodeColumns(node_);
  ASSERT_EQ(columns.rows(), expected.rows());
  EXPECT_LT((columns - expected).norm(), 1e-9 * expected.norm()) << (columns - expected).norm();
  EXPECT_GT(expected.norm(), 0.0);
  // The springs make it stiffer: the same column without them is larger.
  const Eigen::MatrixXd free_columns = BodyColumns(0 * k_, 0 * c_, node_);
  EXPECT_GT(free_columns.norm(), 1.01 * expected.norm());
}

// A load spread over nodes (a jaw's footprint) in one solve: by linearity the weighted sum of the
// nodes' own columns; a fixed node's share moves nothing; a node out of range is refused by name.
TEST_F(FemRestComplianceTest, LoadColumnsAreTheWeightedSumOfTheNodesColumns) {
  FemRestCompliance compliance(model_);
  compliance.SetAttachments(k_, c_);
  const int fixed = fixed_.front().node;
  const std::vector<std::pair<int, double>> load{{node_, 0.5}, {node_ - 1, 0.3}, {node_ - 8, 0.2}, {fixed, 0.4}};
  const Eigen::MatrixXd x = compliance.LoadColumns(load);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(model_->num_dofs(), 3);
  for (const auto& [node, w] : load) sum += w * compliance.NodeColumns(node);
  EXPECT_LT((x - sum).norm(), 1e-10 * sum.norm());
  EXPECT_EQ(x.middleRows(3 * fixed, 3).norm(), 0.0);
  try {
    compliance.LoadColumns({{model_->num_nodes(), 1.0}});
    FAIL();
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("test gallbladder"), std::string::npos) << e.what();
  }
}

TEST_F(FemRestComplianceTest, BackgroundRefactorAnswersFromTheOldFactorUntilAdopted) {
  FemRestCompliance compliance(model_);
  compliance.SetAttachments(k_, c_);
  const Eigen::MatrixXd with_springs = compliance.NodeColumns(node_);
  EXPECT_EQ(compliance.factorizations(), 1);

  const Eigen::VectorXd none = Eigen::VectorXd::Zero(model_->num_dofs());
  compliance.BeginAttachments(none, none);  // every spring cut
  EXPECT_TRUE(compliance.attachments_pending());
  EXPECT_EQ(compliance.NodeColumns(node_), with_springs);  // still the old factor, bit for bit
  compliance.AdoptAttachments();
  EXPECT_FALSE(compliance.attachments_pending());
  EXPECT_EQ(compliance.factorizations(), 2);

  // The same answer as the synchronous path, bit for bit (the same factorisation).
  FemRestCompliance direct(model_);
  direct.SetAttachments(none, none);
  EXPECT_EQ(compliance.NodeColumns(node_), direct.NodeColumns(node_));
  const Eigen::MatrixXd expected = BodyColumns(none, none, node_);
  EXPECT_LT((compliance.NodeColumns(node_) - expected).norm(), 1e-9 * expected.norm());
  compliance.AdoptAttachments();  // nothing pending: nothing changes
  EXPECT_EQ(compliance.factorizations(), 2);
}

// The scene's path: the FEM body's worker factorises S0 for the new attachments once, and the
// compliance's worker waits for that factor instead of factorising S0 again.
TEST_F(FemRestComplianceTest, SharesTheBodysPendingRestFactor) {
  FemSettings s = model_->settings;
  s.element_model = ElementModel::kCorotational;
  s.solver = LinearSolverKind::kRotatedFactorPcg;
  const auto model = std::make_shared<const FemModel>(BuildFemModel(mesh_, s, fixed_));
  FemBody body(model);
  body.Step();  // factorises S0 without attachments
  EXPECT_FALSE(body.PendingRestFactor().valid());
  body.SetAttachmentStiffness(k_, c_);
  const RestFactorFuture shared = body.PendingRestFactor();
  ASSERT_TRUE(shared.valid());

  FemRestCompliance compliance(model);
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(model->num_dofs());
  compliance.SetAttachments(none, none);
  compliance.BeginAttachments(k_, c_, shared);
  compliance.AdoptAttachments();
  EXPECT_EQ(shared.get().use_count(), 2);  // the future's and the compliance's: the same factor
  FemRestCompliance own(model);
  own.SetAttachments(k_, c_);
  EXPECT_EQ(compliance.NodeColumns(node_), own.NodeColumns(node_));  // the same S0, bit for bit
}

TEST_F(FemRestComplianceTest, SharedFactorThatFailedIsReportedAtAdoption) {
  FemRestCompliance compliance(model_);
  compliance.SetAttachments(k_, c_);
  const Eigen::MatrixXd before = compliance.NodeColumns(node_);
  std::promise<std::shared_ptr<const CholmodSolver>> failed;
  failed.set_value(nullptr);  // the body's worker found S0 not positive definite
  compliance.BeginAttachments(k_, c_, failed.get_future().share());
  try {
    compliance.AdoptAttachments();
    FAIL() << "a failed shared factor was adopted";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("test gallbladder"), std::string::npos) << e.what();
  }
  EXPECT_EQ(compliance.NodeColumns(node_), before);  // the current factor stays
}

TEST_F(FemRestComplianceTest, BadAttachmentsAreRejectedNamingTheBody) {
  FemRestCompliance compliance(model_);
  Eigen::VectorXd bad = k_;
  bad[3 * node_] = -1.0;
  EXPECT_THROW(
      {
        try {
          compliance.BeginAttachments(bad, c_);
        } catch (const FemError& e) {
          EXPECT_NE(std::string(e.what()).find("test gallbladder"), std::string::npos) << e.what();
          throw;
        }
      },
      FemError);
  EXPECT_FALSE(compliance.attachments_pending());
  EXPECT_THROW(compliance.SetAttachments(k_.head(3), c_), FemError);
}

}  // namespace
}  // namespace vesica::physics
