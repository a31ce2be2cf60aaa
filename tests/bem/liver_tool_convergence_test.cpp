// Issue 37's convergence study, liver (tools/convergence/liver_hook_study.h): the hook's tip on
// the trainer's liver by the BEM at the trainer's resolution and graded finer toward the contact,
// against the converged CalculiX reference (tests/bem/data/liver_hook_reference.txt, made by
// tools/convergence/reference.py). Prints the table docs/fidelity.md quotes, checks the rate, and
// holds today's errors so a regression fails.

#include <gtest/gtest.h>

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

  std::vector<LiverHookResult> rows;
  std::printf("reference |F| = %.4f N\nlevels vertices edge_mm |F|_N force_err displ_err\n", ref.force_N.norm());
  for (int levels = 0; levels <= 2; ++levels) {
    rows.push_back(SolveLiverHook(liver, ref, MakeLiverHookSetup(liver, ref, levels)));
    const LiverHookResult& r = rows.back();
    std::printf("%d %d %.2f %.4f %.4f %.4f footprint-only: %.4f %.4f\n", levels, r.vertices, 1e3 * r.contact_edge_m,
                r.force_N.norm(), r.force_error, r.displacement_error, r.footprint_force_N.norm(),
                r.footprint_force_error);
  }
  const double rate =
      std::log(rows[0].force_error / rows[2].force_error) / std::log(rows[0].contact_edge_m / rows[2].contact_edge_m);
  std::printf("force error rate (log-log slope in the footprint's edge): %.2f\n", rate);

  // Each finer grading is closer to the continuum, at about first order in h at the tool.
  EXPECT_LT(rows[1].force_error, rows[0].force_error);
  EXPECT_LT(rows[2].force_error, rows[1].force_error);
  EXPECT_GT(rate, 0.7);
  // Today's figures (docs/fidelity.md), held so that a regression fails; a fix updates them. The
  // trainer's liver (level 0) is 40 % stiffer than the continuum under the hook.
  EXPECT_NEAR(rows[0].force_error, 0.401, 0.01);
  EXPECT_NEAR(rows[1].force_error, 0.215, 0.01);
  EXPECT_NEAR(rows[2].force_error, 0.126, 0.01);
  EXPECT_NEAR(rows[0].displacement_error, 0.076, 0.01);
  EXPECT_LT(rows[1].displacement_error, 0.04);
  EXPECT_LT(rows[2].displacement_error, 0.04);
  EXPECT_GT(rows[0].force_N.dot(ref.force_N), 0.99 * rows[0].force_N.norm() * ref.force_N.norm());  // same direction
}

}  // namespace
}  // namespace vesica::convergence
