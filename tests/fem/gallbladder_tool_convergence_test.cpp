// Issue 37's convergence study, gallbladder (tools/convergence/gallbladder_grasp_study.h): the
// trainer's linear-tet FEM on the committed 300 ... 3000-node gallbladders against the converged
// CalculiX reference (tests/fem/data/gallbladder_grasp_reference.txt, tools/convergence/
// reference.py). Prints the table docs/fidelity.md quotes, checks the rate, and holds today's
// errors so a regression fails.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "tools/convergence/gallbladder_grasp_study.h"
#include "tools/convergence/liver_hook_study.h"

namespace vesica::convergence {
namespace {

TEST(GallbladderToolConvergenceTest, JawPullAgainstTheCalculixReference) {
  const std::string root = VESICA_SOURCE_DIR;
  const physics::TriangleMesh liver = ReadTrainerLiver(root);
  const ToolLoadReference ref = ReadGallbladderGraspReference(root);
  ASSERT_GT(ref.jaw_long_axis.norm(), 0.5);

  std::printf("reference |F| = %.5f N\nnodes jaw_nodes edge_mm |F|_N force_err\n", ref.force_N.norm());
  std::vector<GallbladderGraspResult> rows;
  for (int n : {300, 600, 1000, 1600, 3000}) {
    rows.push_back(SolveGallbladderGrasp(ReadTrainerGallbladder(root, n), liver, ref));
    const GallbladderGraspResult& r = rows.back();
    std::printf("%d %d %.2f %.5f %.4f\n", r.nodes, r.jaw_nodes, 1e3 * r.mean_edge_m, r.force_N.norm(), r.force_error);
  }
  const double rate = std::log(rows.front().force_error / rows.back().force_error) /
                      std::log(rows.front().mean_edge_m / rows.back().mean_edge_m);
  std::printf("force error rate (log-log slope in the mean surface edge): %.2f\n", rate);
  // The finest mesh is closer than the coarsest; in between the force follows which nodes fall in
  // the jaw (1, 4, 4, 4, 10) more than the mesh size, so the sequence is not monotone.
  EXPECT_LT(rows.back().force_error, rows.front().force_error);
  // Today's figures against the committed reference (docs/fidelity.md; it is CalculiX's level 4,
  // still moving by 2 % a level), held so that a regression fails; a fix updates them.
  const double today[] = {0.228, 0.173, 0.057, 0.064, 0.051};
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(rows[i].force_error, today[i], 0.01) << rows[i].nodes;
  EXPECT_LT(rows[2].force_error, 0.10);  // the trainer's gallbladder_1000
}

}  // namespace
}  // namespace vesica::convergence
