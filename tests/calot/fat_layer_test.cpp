// The triangle's fat layer: cautery removes exactly the cells the hook reaches once they took
// their removal energy; spreading the jaws parts the layer; the fractions it reports add up
// (docs/calot.md).
#include "physics/calot/fat_layer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace vesica::physics::calot {
namespace {

constexpr int kArtery = 1;

struct Triangle {
  TriangleStructures structures{DefaultTriangleDescription()};
  FatLayer fat{DefaultFatLayerDescription(structures.description()), structures};
};

Eigen::Vector3d Centroid(const FatLayerDescription& d) {
  return (d.corners_m[0] + d.corners_m[1] + d.corners_m[2]) / 3.0;
}

TEST(FatLayerTest, CoversTheTriangleAndHidesEveryTube) {
  Triangle t;
  const std::vector<FatCell>& cells = t.fat.cells();
  EXPECT_GT(cells.size(), 500u);
  EXPECT_LT(cells.size(), 5000u);
  EXPECT_GT(std::count_if(cells.begin(), cells.end(), [](const FatCell& c) { return c.in_triangle; }), 200);
  for (int tube = 0; tube < t.structures.num_tubes(); ++tube)
    EXPECT_DOUBLE_EQ(t.fat.UncoveredFraction(tube), 0.0) << tube;
  EXPECT_DOUBLE_EQ(t.fat.RemovedFraction(), 0.0);
  for (std::size_t i = 0; i < cells.size(); ++i) EXPECT_DOUBLE_EQ(t.fat.Integrity(static_cast<int>(i)), 1.0);
}

TEST(FatLayerTest, BurningRemovesExactlyTheRegionsCellsAtTheStatedDose) {
  Triangle t;
  const Eigen::Vector3d hook = Centroid(t.fat.description());
  const double radius = 0.003, power = 30.0, dt = 0.005;
  std::vector<int> region;  // found here from the cells' positions, apart from the model
  for (std::size_t i = 0; i < t.fat.cells().size(); ++i)
    if ((t.fat.cell_positions_m()[i] - hook).norm() <= radius) region.push_back(static_cast<int>(i));
  ASSERT_GT(region.size(), 5u);
  // Each region cell takes power dt / n a step: removal after E n / (power dt) steps.
  const double steps_exact = t.fat.CellRemovalEnergy_J() * static_cast<double>(region.size()) / (power * dt);
  ASSERT_GT(steps_exact - std::floor(steps_exact), 0.05);  // not on a step boundary
  const int steps = static_cast<int>(std::ceil(steps_exact));
  for (int k = 0; k + 1 < steps; ++k) ASSERT_EQ(t.fat.Burn(hook, radius, power, dt), 0) << "step " << k;
  for (int i : region) EXPECT_NEAR(t.fat.Integrity(i), 1.0 - (steps - 1) / steps_exact, 1e-9);
  EXPECT_EQ(t.fat.Burn(hook, radius, power, dt), static_cast<int>(region.size()));
  for (std::size_t i = 0; i < t.fat.cells().size(); ++i) {
    const bool in_region = std::find(region.begin(), region.end(), static_cast<int>(i)) != region.end();
    EXPECT_EQ(t.fat.cells()[i].state, in_region ? FatCellState::kBurnt : FatCellState::kIntact) << i;
  }
  EXPECT_DOUBLE_EQ(t.fat.BurntFraction(),
                   static_cast<double>(region.size()) / static_cast<double>(t.fat.cells().size()));
  // The hook in the cleared hole, or away from the layer, burns nothing more.
  EXPECT_EQ(t.fat.Burn(hook, radius, power, dt), 0);
  EXPECT_EQ(t.fat.Burn(hook + Eigen::Vector3d(0.2, 0, 0), radius, power, dt), 0);
  EXPECT_THROW(t.fat.Burn(hook, -1.0, power, dt), std::invalid_argument);
}

TEST(FatLayerTest, SpreadingTheJawsPartsTheLayer) {
  Triangle t;
  const FatLayerDescription& d = t.fat.description();
  const Eigen::Vector3d centre = Centroid(d);
  const Eigen::Vector3d along = (d.corners_m[1] - d.corners_m[0]).normalized();  // in the triangle's plane
  const double tip_radius = 0.0015, half_width = 0.006;
  for (int k = 0; k <= 60; ++k) {  // the jaws open from closed to 12 mm apart, 0.1 mm a step each
    const double opening = half_width * k / 60.0;
    t.fat.Push(centre + opening * along, tip_radius);
    t.fat.Push(centre - opening * along, tip_radius);
    t.structures.Step(d.corners_m[1]);
    t.fat.Update(t.structures);
  }
  EXPECT_GT(t.fat.TornFraction(), 0.0);
  EXPECT_DOUBLE_EQ(t.fat.BurntFraction(), 0.0);
  // Parted: no intact cell is left in the channel the tips swept.
  for (double a = -half_width; a <= half_width; a += 0.0005)
    for (std::size_t i = 0; i < t.fat.cells().size(); ++i) {
      if (t.fat.cells()[i].state != FatCellState::kIntact) continue;
      ASSERT_GT((t.fat.cell_positions_m()[i] - (centre + a * along)).norm(), 0.9 * tip_radius) << "a = " << a;
    }
  // Beyond the jaws' reach nothing moved or tore.
  for (std::size_t i = 0; i < t.fat.cells().size(); ++i) {
    const FatCell& cell = t.fat.cells()[i];
    if ((cell.p_Rest_W_m - centre).norm() > half_width + tip_radius + 1e-6) {
      EXPECT_EQ(cell.state, FatCellState::kIntact);
      EXPECT_EQ(cell.displacement_m.norm(), 0.0);
    }
  }
}

TEST(FatLayerTest, FractionsAddUpAndBurntTubeLengthIsUncovered) {
  Triangle t;
  const double from = 0.020, to = 0.030, hook_radius = 0.006;
  // The hook along the artery's middle, staying at each point until nothing within its reach is left.
  for (double s = from; s <= to + 1e-9; s += 0.001) {
    const Eigen::Vector3d hook = t.structures.PositionAt(kArtery, s);
    auto left = [&] {
      int n = 0;
      for (std::size_t i = 0; i < t.fat.cells().size(); ++i)
        n += t.fat.cells()[i].state == FatCellState::kIntact &&
             (t.fat.cell_positions_m()[i] - hook).norm() <= hook_radius;
      return n;
    };
    for (int k = 0; k < 20000 && left() > 0; ++k) t.fat.Burn(hook, hook_radius, 200.0, 0.005);
    ASSERT_EQ(left(), 0);
  }
  t.fat.Push(Centroid(t.fat.description()) + Eigen::Vector3d(0.0, 0.0, 0.0), 0.004);
  t.fat.Update(t.structures);
  const double n = static_cast<double>(t.fat.cells().size());
  const auto intact = std::count_if(t.fat.cells().begin(), t.fat.cells().end(),
                                    [](const FatCell& c) { return c.state == FatCellState::kIntact; });
  EXPECT_GT(t.fat.BurntFraction(), 0.0);
  EXPECT_GT(t.fat.TornFraction(), 0.0);
  EXPECT_NEAR(t.fat.BurntFraction() + t.fat.TornFraction() + static_cast<double>(intact) / n, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(t.fat.RemovedFraction(), t.fat.BurntFraction() + t.fat.TornFraction());
  // The burnt stretch of the artery is bare, and little more than it: the hook reaches past
  // each end by its radius.
  const double bare_m = t.fat.UncoveredFraction(kArtery) * t.structures.TubeLength_m(kArtery);
  EXPECT_GE(bare_m, (to - from) - 0.001);
  EXPECT_LE(bare_m, (to - from) + 2 * hook_radius);
  EXPECT_GT(t.fat.TriangleClearedFraction(), 0.0);
  EXPECT_LT(t.fat.TriangleClearedFraction(), 1.0);
}

TEST(FatLayerTest, BadDescriptionIsRefusedWithTheFieldsName) {
  TriangleStructures structures(DefaultTriangleDescription());
  FatLayerDescription d = DefaultFatLayerDescription(structures.description());
  d.cell_spacing_m = 0.0;
  try {
    FatLayer fat(d, structures);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cell_spacing_m"), std::string::npos);
  }
  d = DefaultFatLayerDescription(structures.description());
  d.corners_m[2] = d.corners_m[0] + 2.0 * (d.corners_m[1] - d.corners_m[0]);
  EXPECT_THROW(FatLayer(d, structures), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics::calot
