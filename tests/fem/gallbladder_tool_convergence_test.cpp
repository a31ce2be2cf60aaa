// Issue 37's convergence study, gallbladder (tools/convergence/gallbladder_grasp_study.h): the
// trainer's linear-tet FEM, and the candidate elements (the average-nodal-pressure tet, 10-node
// tets), on the committed 300 ... 3000-node gallbladders against the CalculiX references
// (tests/fem/data/gallbladder_{grasp,press}_reference.txt, made by tools/convergence/reference.py
// on the exact 10 x 5 mm jaw; level 4, 175k nodes, converged: 0.46 / 0.53 % from level 3), the jaw pulled (all
// components held) and pressed (frictionless), with the jaw as the nodes inside it or as its
// footprint's consistent weights (physics/fem/jaw_footprint.h). Prints the tables
// docs/fidelity.md quotes and holds their figures.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "tools/convergence/gallbladder_grasp_study.h"
#include "tools/convergence/liver_hook_study.h"

namespace vesica::convergence {
namespace {

constexpr int kMeshes[] = {300, 600, 1000, 1600, 3000};

std::vector<GallbladderGraspResult> Study(JawModel model, JawLoad load,
                                          TetFormulation formulation = TetFormulation::kLinear) {
  const std::string root = VESICA_SOURCE_DIR;
  const physics::TriangleMesh liver = ReadTrainerLiver(root);
  const ToolLoadReference ref =
      load == JawLoad::kPull ? ReadGallbladderGraspReference(root) : ReadGallbladderPressReference(root);
  std::printf("%s, %s, %s: reference |F| = %.5f N\nnodes dof_nodes jaw_nodes edge_mm |F|_N force_err\n",
              TetFormulationName(formulation), JawModelName(model), load == JawLoad::kPull ? "pull" : "press",
              ref.force_N.norm());
  std::vector<GallbladderGraspResult> rows;
  for (int n : kMeshes) {
    rows.push_back(SolveGallbladderGrasp(ReadTrainerGallbladder(root, n), liver, ref, model, load, formulation));
    const GallbladderGraspResult& r = rows.back();
    std::printf("%d %d %d %.2f %.5f %.4f\n", r.nodes, r.dof_nodes, r.jaw_nodes, 1e3 * r.mean_edge_m, r.force_N.norm(),
                r.force_error);
  }
  return rows;
}

// Log-log slope of the force error in the mean surface edge, coarsest to finest.
double Rate(const std::vector<GallbladderGraspResult>& rows) {
  return std::log(rows.front().force_error / rows.back().force_error) /
         std::log(rows.front().mean_edge_m / rows.back().mean_edge_m);
}

// Held force errors per mesh (300, 600, 1000, 1600, 3000 nodes) of the candidate elements.
const std::vector<double> kNodalPressurePull = {0.273, 0.172, 0.125, 0.078, 0.018};
const std::vector<double> kNodalPressurePress = {0.254, 0.165, 0.127, 0.078, 0.023};
const std::vector<double> kQuadraticPull = {0.026, 0.041, 0.050, 0.059, 0.067};
const std::vector<double> kQuadraticPress = {0.006, 0.039, 0.044, 0.055, 0.061};
const std::vector<double> kQuadraticCellsPull = {0.246, 0.016, 0.010, 0.025, 0.040};
const std::vector<double> kQuadraticCellsPress = {0.192, 0.003, 0.006, 0.025, 0.037};

void ExpectFigures(const std::vector<GallbladderGraspResult>& rows, const std::vector<double>& held) {
  ASSERT_EQ(rows.size(), held.size());
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(rows[i].force_error, held[i], 0.01) << rows[i].nodes;
}

// Both jaw models on both loads. The footprint's weights take the mesh's dependence on which
// nodes fall inside the jaw away: its force comes down toward the reference with every finer mesh
// (first order, from above: the linear tets are too stiff under a 10 x 5 mm jaw with 2-6 mm
// edges). The nodes inside (1, 4, 4, 4, 10 of them) scatter around it instead; at the trainer's
// 1,003 nodes their smaller footprint happens to offset the stiffness.
void CheckLoad(JawLoad load, const std::vector<double>& nodes_inside_held, const std::vector<double>& footprint_held) {
  const std::vector<GallbladderGraspResult> inside = Study(JawModel::kNodesInside, load);
  const std::vector<GallbladderGraspResult> footprint = Study(JawModel::kFootprintMean, load);
  std::printf("footprint force error rate (log-log slope in the mean surface edge): %.2f\n", Rate(footprint));
  for (std::size_t i = 0; i + 1 < footprint.size(); ++i)
    EXPECT_LT(footprint[i + 1].force_error, footprint[i].force_error) << footprint[i + 1].nodes;
  EXPECT_GT(Rate(footprint), 0.8);
  ExpectFigures(inside, nodes_inside_held);
  ExpectFigures(footprint, footprint_held);
  EXPECT_LT(inside[2].force_error, 0.10);  // the trainer's gallbladder_1000, the nodes inside the jaw
}

TEST(GallbladderToolConvergenceTest, JawPulledAgainstTheCalculixReference) {
  CheckLoad(JawLoad::kPull, {0.220, 0.186, 0.068, 0.054, 0.063}, {0.588, 0.356, 0.290, 0.215, 0.115});
}

TEST(GallbladderToolConvergenceTest, JawPressedAgainstTheCalculixReference) {
  CheckLoad(JawLoad::kPress, {0.217, 0.162, 0.067, 0.064, 0.055}, {0.541, 0.349, 0.280, 0.211, 0.119});
}

// The candidates for a jaw-independent force within 10 % at the trainer's 1,003 nodes
// (physics/fem/small_strain_stiffness.h), with the footprint's weights: the average-nodal-pressure
// linear tet (no volumetric locking, the same nodes) and 10-node tets on the same mesh. The jaw's
// mean (one uniform traction) has its own continuum limit, below the rigid jaw the reference
// prescribes (a rigid punch is stiffer than a uniform traction of the same mean displacement: 8 %
// for a disc on a half-space); the 4 x 2 cells (a traction constant on each 2.5 x 2.5 mm cell)
// come closer to it. So the 10-node tets' force settles (its change between meshes falls to
// under 1 %) a few per cent below the reference, and its error against the rigid jaw grows
// slowly as the mesh refines; the nodal-pressure tet comes down from above at about third order.
// Held: the force error against the reference per mesh.
std::vector<GallbladderGraspResult> CheckCandidate(TetFormulation formulation, JawModel jaw, JawLoad load,
                                                   const std::vector<double>& held) {
  const std::vector<GallbladderGraspResult> rows = Study(jaw, load, formulation);
  std::printf("force error rate (log-log slope in the mean surface edge, coarsest to finest): %.2f\n", Rate(rows));
  std::printf("force change between successive meshes:");
  for (std::size_t i = 0; i + 1 < rows.size(); ++i)
    std::printf(" %.2f %%",
                100.0 * std::abs(rows[i + 1].force_N.norm() - rows[i].force_N.norm()) / rows[i + 1].force_N.norm());
  std::printf("\n");
  ExpectFigures(rows, held);
  return rows;
}

// The nodal-pressure tet: from above, every finer mesh closer, faster than the linear tet's 1.7-1.8.
void ExpectComingDownFromAbove(const std::vector<GallbladderGraspResult>& rows, const ToolLoadReference& ref) {
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    EXPECT_GT(rows[i].force_N.norm(), ref.force_N.norm()) << rows[i].nodes;
    EXPECT_LT(rows[i + 1].force_error, rows[i].force_error) << rows[i + 1].nodes;
  }
  EXPECT_GT(Rate(rows), 2.5);
}

// The 10-node tets from the trainer's mesh on: within 10 % and settled (the force moves by under
// 2.5 % between successive meshes; the cells' limit lies closer to the rigid jaw's).
void ExpectWithinTenPercentAndSettled(const std::vector<GallbladderGraspResult>& rows) {
  for (std::size_t i = 2; i < rows.size(); ++i) {
    EXPECT_LT(rows[i].force_error, 0.10) << rows[i].nodes;
    EXPECT_LT(std::abs(rows[i].force_N.norm() - rows[i - 1].force_N.norm()), 0.025 * rows[i].force_N.norm())
        << rows[i].nodes;
  }
}

TEST(GallbladderToolConvergenceTest, NodalPressureTetsPulled) {
  ExpectComingDownFromAbove(
      CheckCandidate(TetFormulation::kNodalPressure, JawModel::kFootprintMean, JawLoad::kPull, kNodalPressurePull),
      ReadGallbladderGraspReference(VESICA_SOURCE_DIR));
}

TEST(GallbladderToolConvergenceTest, NodalPressureTetsPressed) {
  ExpectComingDownFromAbove(
      CheckCandidate(TetFormulation::kNodalPressure, JawModel::kFootprintMean, JawLoad::kPress, kNodalPressurePress),
      ReadGallbladderPressReference(VESICA_SOURCE_DIR));
}

// gallbladder_1000 (the trainer's) and finer with 10-node tets: both jaw models within 10 %.
TEST(GallbladderToolConvergenceTest, QuadraticTetsPulledWithinTenPercentFromTheTrainersMesh) {
  ExpectWithinTenPercentAndSettled(
      CheckCandidate(TetFormulation::kQuadratic, JawModel::kFootprintMean, JawLoad::kPull, kQuadraticPull));
  ExpectWithinTenPercentAndSettled(
      CheckCandidate(TetFormulation::kQuadratic, JawModel::kFootprintCells, JawLoad::kPull, kQuadraticCellsPull));
}

TEST(GallbladderToolConvergenceTest, QuadraticTetsPressedWithinTenPercentFromTheTrainersMesh) {
  ExpectWithinTenPercentAndSettled(
      CheckCandidate(TetFormulation::kQuadratic, JawModel::kFootprintMean, JawLoad::kPress, kQuadraticPress));
  ExpectWithinTenPercentAndSettled(
      CheckCandidate(TetFormulation::kQuadratic, JawModel::kFootprintCells, JawLoad::kPress, kQuadraticCellsPress));
}

// The trainer's grasp (physics/fem/jaw_subgrid_compliance.h, what physics/scene builds): the
// linear tets with the jaw as its footprint's mean, in series with the subgrid compliance (on the
// patch of tets within 15 mm of the jaw, the 10-node tets' 4 x 2-cell jaw less the linear tets'
// mean). Within 10 % of the reference from the trainer's mesh on, pulled and pressed, and
// converging: the corrected force is settled (moves by under 2.5 % a mesh) from 600 nodes.
void ExpectTrainersGrasp(JawLoad load, const std::vector<double>& held) {
  const std::vector<GallbladderGraspResult> rows =
      CheckCandidate(TetFormulation::kLinear, JawModel::kFootprintMeanWithSubgrid, load, held);
  ExpectWithinTenPercentAndSettled(rows);
}

TEST(GallbladderToolConvergenceTest, TrainersGraspPulledWithTheSubgridCompliance) {
  ExpectTrainersGrasp(JawLoad::kPull, {0.269, 0.031, 0.009, 0.014, 0.036});
}

TEST(GallbladderToolConvergenceTest, TrainersGraspPressedWithTheSubgridCompliance) {
  ExpectTrainersGrasp(JawLoad::kPress, {0.221, 0.021, 0.011, 0.014, 0.033});
}

// The patch's radius: on gallbladder_1000 the trainer's force moves 2.7 % from a 10 to a 15 mm
// patch, then about 1 % per 5 mm (the held cut cancels in the difference to first order; the
// patch then reaches the held bed): 15 mm, the scene's, is within 2 % of 25 mm, and every patch
// from 15 mm is within 2 % of the reference.
TEST(GallbladderToolConvergenceTest, TrainersGraspSettlesWithThePatchRadius) {
  const std::string root = VESICA_SOURCE_DIR;
  const physics::TriangleMesh liver = ReadTrainerLiver(root);
  const ToolLoadReference ref = ReadGallbladderGraspReference(root);
  const physics::TetrahedralMesh mesh = ReadTrainerGallbladder(root, 1000);
  std::vector<double> forces;
  for (double radius : {0.010, 0.015, 0.020, 0.025}) {
    physics::JawSubgridSettings settings;
    settings.patch_radius_m = radius;
    const GallbladderGraspResult r = SolveGallbladderGrasp(mesh, liver, ref, JawModel::kFootprintMeanWithSubgrid,
                                                           JawLoad::kPull, TetFormulation::kLinear, settings);
    std::printf("patch radius %.0f mm: |F| = %.5f N, error %.4f\n", 1e3 * radius, r.force_N.norm(), r.force_error);
    forces.push_back(r.force_N.norm());
  }
  EXPECT_LT(std::abs(forces[1] - forces[3]), 0.02 * forces[3]);
  EXPECT_LT(std::abs(forces[2] - forces[3]), std::abs(forces[0] - forces[3]));
  for (std::size_t i = 1; i < forces.size(); ++i)
    EXPECT_LT(std::abs(forces[i] - ref.force_N.norm()), 0.02 * ref.force_N.norm()) << i;
}

}  // namespace
}  // namespace vesica::convergence
