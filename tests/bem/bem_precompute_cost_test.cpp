// The BEM precompute's cost is known before it starts: a surface too large for the dense
// blocks is refused with the memory and time it would take (a 5,008-vertex liver ran silent for
// minutes and 5 GB), a long one is announced, and a running one reports its progress.

#include "physics/bem/bem_precompute_cost.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "bem_test_support.h"
#include "physics/bem/bem_errors.h"
#include "physics/bem/bem_model.h"

namespace vesica::physics {
namespace {

TEST(BemPrecomputeCostTest, PeakMemoryIsTheDenseBlocks) {
  // H and G (3n x 3n) and Xi (3n x 3 n_free), 8 bytes each entry.
  const BemPrecomputeCost cost = EstimateBemPrecomputeCost(1000, 900);
  EXPECT_EQ(cost.peak_bytes, 8ull * 3000 * (2 * 3000 + 2700));
  EXPECT_GT(cost.seconds, 0.0);
  EXPECT_GT(EstimateBemPrecomputeCost(2000, 1800).seconds, 4.0 * cost.seconds);  // at least n^2
}

TEST(BemPrecomputeCostTest, DescriptionNamesVerticesMemoryAndTime) {
  const std::string text = DescribeBemPrecomputeCost(5008, {5'234'000'000, 400.0});
  EXPECT_EQ(text, "5008 vertices: about 5.2 GB of memory and 7 min");
  EXPECT_EQ(DescribeBemPrecomputeCost(60, {1'200'000, 0.2}), "60 vertices: about 2 MB of memory and 1 s");
}

TEST(BemPrecomputeCostTest, ALiverOfFiveThousandVerticesIsRefusedBeforeAnyComputation) {
  const TriangleMesh mesh = testing::LiverLikeEllipsoid(5008);
  try {
    PrecomputeBemModel(mesh, LiverMaterial(), "liver-5008.obj");
    FAIL() << "a 5008-vertex surface was precomputed";
  } catch (const BemError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("liver-5008.obj: too large for the BEM liver: " + std::to_string(mesh.num_vertices()) +
                        " vertices: about 5."),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("GB of memory and"), std::string::npos) << what;
    EXPECT_NE(what.find("decimate"), std::string::npos) << what;
  }
}

TEST(BemPrecomputeCostTest, LimitAndWarningThresholdAreTheCallers) {
  const TriangleMesh mesh = testing::LiverLikeEllipsoid(60);
  BemPrecomputeOptions options;
  options.max_peak_bytes = 100'000;
  EXPECT_THROW(PrecomputeBemModel(mesh, LiverMaterial(), "small", options), BemError);
  options.max_peak_bytes = 0;  // no limit
  options.warn_after_s = 0.0;  // every precompute is "long"
  std::vector<std::string> warnings;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  PrecomputeBemModel(mesh, LiverMaterial(), "small", options);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind("small: the BEM precompute of " + std::to_string(mesh.num_vertices()) + " vertices", 0),
            0u)
      << warnings[0];
}

TEST(BemPrecomputeCostTest, PrecomputeReportsItsProgress) {
  BemPrecomputeOptions options;
  std::vector<std::pair<BemPrecomputeStage, double>> reports;
  options.on_progress = [&](BemPrecomputeStage stage, double f) { reports.emplace_back(stage, f); };
  PrecomputeBemModel(testing::LiverLikeEllipsoid(400), LiverMaterial(), "progress", options);
  ASSERT_GE(reports.size(), 4u);
  // Assembly fractions rise to 1, then the solve's start and end.
  double last = 0;
  std::size_t i = 0;
  for (; i < reports.size() && reports[i].first == BemPrecomputeStage::kAssembly; ++i) {
    EXPECT_GT(reports[i].second, last);
    last = reports[i].second;
  }
  EXPECT_GE(i, 2u);  // at least one report before the end of the assembly
  EXPECT_EQ(last, 1.0);
  ASSERT_EQ(reports.size(), i + 2);
  EXPECT_EQ(reports[i], std::make_pair(BemPrecomputeStage::kSolve, 0.0));
  EXPECT_EQ(reports[i + 1], std::make_pair(BemPrecomputeStage::kSolve, 1.0));
}

}  // namespace
}  // namespace vesica::physics
