// Issue 37's convergence study, liver (tools/convergence/liver_hook_study.h): the hook's tip on
// the trainer's liver by the BEM at the trainer's resolution and graded finer toward the contact,
// against the converged CalculiX reference (tests/bem/data/liver_hook_reference.txt, made by
// tools/convergence/reference.py), in two formulations:
//   nodes  the footprint's vertices prescribed (BemCapacitanceSolver): 40 % stiff, first order
//   modes  the footprint as traction modes (BemFootprintSolver, physics/bem/tool_footprint.h):
//          the fix, within 10 % on the trainer's mesh and converging at second order
// Prints the table docs/fidelity.md quotes, checks the rates, and holds the figures so that a
// regression fails.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tools/convergence/liver_hook_study.h"

namespace vesica::convergence {
namespace {

TEST(LiverToolConvergenceTest, HookIndentationConvergesTowardTheCalculixReference) {
  const std::string root = VESICA_SOURCE_DIR;
  const physics::TriangleMesh liver = ReadTrainerLiver(root);
  const ToolLoadReference ref = ReadLiverHookReference(root);
  ASSERT_EQ(ref.displacement_m.rows(), liver.num_vertices());

  std::vector<LiverHookResult> nodes, modes;
  std::printf(
      "reference |F| = %.4f N\n"
      "levels vertices edge_mm | nodes: |F|_N force_err displ_err | modes: |F|_N force_err displ_err\n",
      ref.force_N.norm());
  const auto solve = [&](int levels, LiverGrading grading, const char* name) {
    const LiverHookSetup setup = MakeLiverHookSetup(liver, ref, levels, grading);
    const physics::BemModel model = physics::PrecomputeBemModel(setup.surface, physics::LiverMaterial(), "study liver");
    nodes.push_back(SolveLiverHook(liver, ref, setup, model));
    modes.push_back(SolveLiverHookWithModes(liver, ref, setup, model));
    const LiverHookResult &a = nodes.back(), &b = modes.back();
    std::printf("%d%s %d %.2f | %.4f %.4f %.4f | %.4f %.4f %.4f\n", levels, name, a.vertices, 1e3 * a.contact_edge_m,
                a.force_N.norm(), a.force_error, a.displacement_error, b.force_N.norm(), b.force_error,
                b.displacement_error);
    std::fflush(stdout);
  };
  std::vector<std::array<double, 2>> disc_N;  // the scene's footprints: hook 1.5 mm, jaws 4 mm
  const auto solve_with_discs = [&](int levels) {
    const LiverHookSetup setup = MakeLiverHookSetup(liver, ref, levels);
    const physics::BemModel model = physics::PrecomputeBemModel(setup.surface, physics::LiverMaterial(), "study liver");
    nodes.push_back(SolveLiverHook(liver, ref, setup, model));
    modes.push_back(SolveLiverHookWithModes(liver, ref, setup, model));
    disc_N.push_back(
        {LiverDiscPushForce(liver, ref, setup, model, 0.0015), LiverDiscPushForce(liver, ref, setup, model, 0.004)});
    const LiverHookResult &a = nodes.back(), &b = modes.back();
    std::printf("%d %d %.2f | %.4f %.4f %.4f | %.4f %.4f %.4f | discs 1.5 / 4 mm: %.4f %.4f N\n", levels, a.vertices,
                1e3 * a.contact_edge_m, a.force_N.norm(), a.force_error, a.displacement_error, b.force_N.norm(),
                b.force_error, b.displacement_error, disc_N.back()[0], disc_N.back()[1]);
    std::fflush(stdout);
  };
  for (int levels = 0; levels <= 2; ++levels) solve_with_discs(levels);
  solve(1, LiverGrading::kTowardBed, " (bed)");

  // Nodes prescribed: each finer grading is closer, at about first order in h at the tool.
  const double node_rate = std::log(nodes[0].force_error / nodes[2].force_error) /
                           std::log(nodes[0].contact_edge_m / nodes[2].contact_edge_m);
  std::printf("nodes: force error rate (log-log slope in the footprint's edge): %.2f\n", node_rate);
  EXPECT_LT(nodes[1].force_error, nodes[0].force_error);
  EXPECT_LT(nodes[2].force_error, nodes[1].force_error);
  EXPECT_GT(node_rate, 0.7);
  EXPECT_NEAR(nodes[0].force_error, 0.401, 0.01);
  EXPECT_NEAR(nodes[1].force_error, 0.215, 0.01);
  EXPECT_NEAR(nodes[2].force_error, 0.126, 0.01);
  EXPECT_NEAR(nodes[0].displacement_error, 0.076, 0.01);

  // Traction modes: the trainer's own liver (level 0) is within 10 % in force and displacement.
  EXPECT_LT(modes[0].force_error, 0.10);
  EXPECT_LT(modes[0].displacement_error, 0.10);
  EXPECT_NEAR(modes[0].force_error, 0.095, 0.005);  // held: a regression fails
  EXPECT_NEAR(modes[0].displacement_error, 0.072, 0.005);
  // Finer, they settle within the reference's own uncertainty (its last level moved 0.9 %, and
  // its extrapolated limit lies 1-2 % below it): the graded livers are within 3 % in force.
  for (int k = 1; k <= 3; ++k) {
    EXPECT_LT(modes[static_cast<std::size_t>(k)].force_error, 0.03) << "row " << k;
    EXPECT_LT(modes[static_cast<std::size_t>(k)].displacement_error, 0.05) << "row " << k;
  }
  // The rate against the finest level (self-convergence, free of the reference's 1-2 %): the
  // footprint's edge halves per level, and the force's change shrinks about 5 times (second
  // order), against 0.8 for the prescribed nodes.
  const double f0 = modes[0].force_N.norm(), f1 = modes[1].force_N.norm(), f2 = modes[2].force_N.norm();
  const double mode_rate =
      std::log(std::abs(f0 - f2) / std::abs(f1 - f2)) / std::log(modes[0].contact_edge_m / modes[1].contact_edge_m);
  const double limit_N = f2 - (f1 - f2) / (std::pow(modes[1].contact_edge_m / modes[2].contact_edge_m, mode_rate) - 1);
  std::printf("modes: self-convergence rate %.2f, Richardson limit %.4f N (reference %.4f N)\n", mode_rate, limit_N,
              ref.force_N.norm());
  EXPECT_GT(mode_rate, 1.5);
  EXPECT_LT(f1, f0);
  EXPECT_LT(f2, f1);
  EXPECT_NEAR(limit_N, ref.force_N.norm(), 0.03 * ref.force_N.norm());
  EXPECT_GT(modes[0].force_N.dot(ref.force_N), 0.99 * modes[0].force_N.norm() * ref.force_N.norm());

  // The scene's own footprints (discs, one normal row): the force falls as the liver is refined,
  // and the hook's 3 mm disc, smaller than the trainer's elements, is still far from converged on
  // them (level 0 is 44 % above level 2); held so that a change shows.
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(disc_N[1][static_cast<std::size_t>(k)], disc_N[0][static_cast<std::size_t>(k)]);
    EXPECT_LT(disc_N[2][static_cast<std::size_t>(k)], disc_N[1][static_cast<std::size_t>(k)]);
  }
  EXPECT_NEAR(disc_N[0][0], 4.09, 0.05);
  EXPECT_NEAR(disc_N[0][1], 5.84, 0.05);
}

}  // namespace
}  // namespace vesica::convergence
