// ChainMail (seed eqs. 3-8, Gibson 1997): closed forms on a chain, slack, bounds after every move,
// fixed elements.
#include "physics/patient/chain_mail.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace vesica::physics {
namespace {

constexpr double kSpacing = 0.01;
constexpr double kTol = 1e-9;  // the bounds are stored in single precision: ~1e-10 m at this size

// A chain of n elements along +x, element k at x = k s.
ChainMail Chain(int n, const ChainMailParameters& p) {
  ChainMail mail(n, p);
  for (int k = 0; k + 1 < n; ++k) mail.Link(k, k + 1, Eigen::Vector3d(kSpacing, 0, 0));
  return mail;
}

// Pulling element 0 by D away from the chain: link k-1 -> k may grow to lambda s, so element k must
// follow once element k-1 is more than (lambda - 1) s ahead of it; by induction element k moves by
// D - k s (lambda - 1), and not at all once that is negative.
TEST(ChainMailTest, PulledChainFollowsTheClosedForm) {
  const ChainMailParameters p{0.9, 1.2, 0.3};
  const int n = 12;
  ChainMail mail = Chain(n, p);
  std::vector<Eigen::Vector3d> u(n, Eigen::Vector3d::Zero());
  const double pull = 0.013;
  const int driver[] = {0};
  const Eigen::Vector3d target[] = {Eigen::Vector3d(-pull, 0, 0)};
  mail.Move(driver, target, u);
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(-u[k].x(), std::max(0.0, pull - k * kSpacing * (p.stretch_lambda - 1.0)), kTol) << k;
    EXPECT_EQ(u[k].y(), 0.0);
    EXPECT_EQ(u[k].z(), 0.0);
  }
  EXPECT_LE(mail.WorstViolation_m(u), kTol);
}

// Pushing it by D into the chain: the link may shrink to gamma s, so element k moves by
// max(0, D - k s (1 - gamma)).
TEST(ChainMailTest, PushedChainFollowsTheClosedForm) {
  const ChainMailParameters p{0.9, 1.2, 0.3};
  const int n = 12;
  ChainMail mail = Chain(n, p);
  std::vector<Eigen::Vector3d> u(n, Eigen::Vector3d::Zero());
  const int driver[] = {0};
  const Eigen::Vector3d target[] = {Eigen::Vector3d(0.0045, 0, 0)};
  mail.Move(driver, target, u);
  for (int k = 0; k < n; ++k)
    EXPECT_NEAR(u[k].x(), std::max(0.0, 0.0045 - k * kSpacing * (1.0 - p.compression_gamma)), kTol) << k;
}

// Moving it sideways by D: each link may shear by mu s, so element k moves by max(0, D - k s mu).
TEST(ChainMailTest, ShearedChainFollowsTheClosedForm) {
  const ChainMailParameters p{0.9, 1.2, 0.3};
  const int n = 12;
  ChainMail mail = Chain(n, p);
  std::vector<Eigen::Vector3d> u(n, Eigen::Vector3d::Zero());
  const int driver[] = {0};
  const Eigen::Vector3d target[] = {Eigen::Vector3d(0, 0, -0.02)};
  mail.Move(driver, target, u);
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(-u[k].z(), std::max(0.0, 0.02 - k * kSpacing * p.shear_mu), kTol) << k;
    EXPECT_EQ(u[k].x(), 0.0);
  }
}

TEST(ChainMailTest, MoveWithinSlackMovesNoNeighbour) {
  const ChainMailParameters p{0.9, 1.1, 0.2};
  const int n = 6;
  ChainMail mail = Chain(n, p);
  std::vector<Eigen::Vector3d> u(n, Eigen::Vector3d::Zero());
  const int driver[] = {2};
  // Within every slack: stretch 1 mm, compression 1 mm, shear 2 mm (s = 1 cm).
  const Eigen::Vector3d target[] = {Eigen::Vector3d(0.0009, 0.0019, -0.0019)};
  const ChainMail::MoveReport report = mail.Move(driver, target, u);
  EXPECT_EQ(report.moved, 0);
  for (int k = 0; k < n; ++k)
    if (k != 2) {
      EXPECT_EQ(u[k], Eigen::Vector3d::Zero()) << k;
    }
}

// A 6 x 6 x 6 lattice with all 26 links, one corner fixed: random moves of random elements keep
// every link within its bounds, and the fixed element never moves.
TEST(ChainMailTest, BoundsHoldAfterEveryMoveAndFixedStays) {
  const int side = 6, n = side * side * side;
  const ChainMailParameters p{0.8, 1.25, 0.3};
  ChainMail mail(n, p);
  const auto id = [&](int i, int j, int k) { return i + side * (j + side * k); };
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i)
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const bool forward = dk > 0 || (dk == 0 && (dj > 0 || (dj == 0 && di > 0)));
              const int a = i + di, b = j + dj, c = k + dk;
              if (!forward || a < 0 || b < 0 || c < 0 || a >= side || b >= side || c >= side) continue;
              mail.Link(id(i, j, k), id(a, b, c), kSpacing * Eigen::Vector3d(di, dj, dk));
            }
  mail.Fix(id(0, 0, 0));
  std::vector<Eigen::Vector3d> u(n, Eigen::Vector3d::Zero());
  std::mt19937 random(33);
  std::uniform_int_distribution<int> pick(1, n - 1);
  std::uniform_real_distribution<double> step(-0.004, 0.004);
  int moves_that_moved_neighbours = 0;
  for (int move = 0; move < 300; ++move) {
    const int driver[] = {pick(random)};
    const Eigen::Vector3d target[] = {u[driver[0]] + Eigen::Vector3d(step(random), step(random), step(random))};
    const ChainMail::MoveReport report = mail.Move(driver, target, u);
    moves_that_moved_neighbours += report.moved > 0;
    ASSERT_LE(mail.WorstViolation_m(u), kTol) << "move " << move;
    ASSERT_EQ(u[id(0, 0, 0)], Eigen::Vector3d::Zero()) << "move " << move;
    if (!report.refused()) {
      EXPECT_EQ(u[driver[0]], target[0]);
    }
  }
  EXPECT_GT(moves_that_moved_neighbours, 100);  // the test exercised propagation, not just slack
}

TEST(ChainMailTest, AtLeastDriversGoAtLeastToTheirTargets) {
  const ChainMailParameters p{0.9, 1.1, 0.1};
  ChainMail mail = Chain(5, p);
  std::vector<Eigen::Vector3d> u(5, Eigen::Vector3d::Zero());
  // Element 1 is asked for 1 mm but element 0, 1 cm ahead, carries it further.
  const int drivers[] = {0, 1};
  const Eigen::Vector3d targets[] = {Eigen::Vector3d(0, 0, 0.01), Eigen::Vector3d(0, 0, 0.001)};
  mail.Move(drivers, targets, u, ChainMail::Drivers::kAtLeast);
  EXPECT_NEAR(u[0].z(), 0.01, kTol);
  EXPECT_NEAR(u[1].z(), 0.01 - kSpacing * p.shear_mu, kTol);
  EXPECT_LE(mail.WorstViolation_m(u), kTol);
}

TEST(ChainMailTest, BadParametersAndLinksAreRefused) {
  EXPECT_THROW(ChainMail(3, ChainMailParameters{1.2, 1.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(ChainMail(3, ChainMailParameters{0.9, 0.9, 0.1}), std::invalid_argument);
  EXPECT_THROW(ChainMail(3, ChainMailParameters{0.9, 1.1, -0.1}), std::invalid_argument);
  ChainMail mail(3, ChainMailParameters{});
  EXPECT_THROW(mail.Link(0, 0, Eigen::Vector3d::UnitX()), std::invalid_argument);
  EXPECT_THROW(mail.Link(0, 3, Eigen::Vector3d::UnitX()), std::invalid_argument);
  EXPECT_THROW(mail.Link(0, 1, Eigen::Vector3d::Zero()), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
