#include "physics/fem/increment_extrapolation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vesica::physics {
namespace {

// Order-p polynomial extrapolation written out (the Lagrange form on equally spaced steps):
// du_{n+1} ~ sum_{j=0..p} (-1)^j C(p+1, j+1) du_{n-j}; history newest first.
Eigen::VectorXd LagrangePrediction(const std::vector<Eigen::VectorXd>& history, int order) {
  Eigen::VectorXd guess = Eigen::VectorXd::Zero(history[0].size());
  double binomial = order + 1;  // C(p+1, 1)
  for (int j = 0; j <= order; ++j) {
    guess += (j % 2 ? -binomial : binomial) * history[j];
    binomial = binomial * (order + 1 - (j + 1)) / (j + 2);  // C(p+1, j+2)
  }
  return guess;
}

// Increment k: entry i follows a polynomial of the given degree in k (different per entry).
Eigen::VectorXd PolynomialIncrement(int k, int degree, int size) {
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) {
    double value = 0.0;
    for (int d = 0; d <= degree; ++d) value += std::sin(1.0 + i + 3.0 * d) * std::pow(0.1 * k, d);
    v[i] = value;
  }
  return v;
}

TEST(IncrementExtrapolationTest, PredictsPolynomialIncrementsExactly) {
  for (int degree = 0; degree <= IncrementExtrapolation::kMaxOrder; ++degree) {
    IncrementExtrapolation e;
    for (int k = 0; k < 10; ++k) e.Push(PolynomialIncrement(k, degree, 7));
    Eigen::VectorXd guess;
    e.Predict(7, guess);
    const Eigen::VectorXd next = PolynomialIncrement(10, degree, 7);
    EXPECT_LT((guess - next).norm(), 1e-9 * next.norm()) << "degree " << degree << ", order " << e.order();
    EXPECT_GE(e.order(), degree) << "a lower order cannot be exact";
  }
}

TEST(IncrementExtrapolationTest, PicksTheOrderThatPredictedTheLastIncrementBestAndMatchesLagrange) {
  // Smooth drift plus noise: each step, the chosen order is the one whose written-out prediction of
  // the newest increment (from the ones before it) missed least, and the prediction is that order's.
  std::vector<Eigen::VectorXd> history;  // newest first
  IncrementExtrapolation e;
  unsigned seed = 12345;
  auto noise = [&]() {
    seed = seed * 1103515245u + 12345u;
    return ((seed >> 8) & 0xffff) / 65536.0 - 0.5;
  };
  int orders_seen = 0;
  for (int k = 0; k < 40; ++k) {
    Eigen::VectorXd du = PolynomialIncrement(k, 3, 5);
    const double amplitude = k < 20 ? 1e-6 : 0.3;  // nearly smooth, then jerky
    for (int i = 0; i < du.size(); ++i) du[i] += amplitude * noise();
    history.insert(history.begin(), du);
    e.Push(du);
    const int available = static_cast<int>(history.size()) - 2;  // orders with a known miss
    if (available < 0) {
      EXPECT_EQ(e.order(), 0);
      continue;
    }
    const std::vector<Eigen::VectorXd> before(history.begin() + 1, history.end());
    int best = 0;
    double best_miss = 1e300;
    for (int p = 0; p <= std::min(available, IncrementExtrapolation::kMaxOrder); ++p) {
      const double miss = (history[0] - LagrangePrediction(before, p)).norm();
      if (miss < best_miss) best_miss = miss, best = p;
    }
    EXPECT_EQ(e.order(), best) << "step " << k;
    orders_seen |= 1 << e.order();
    Eigen::VectorXd guess;
    e.Predict(5, guess);
    const Eigen::VectorXd expected = LagrangePrediction(history, e.order());
    EXPECT_LT((guess - expected).norm(), 1e-12 * (1.0 + expected.norm())) << "step " << k;
  }
  EXPECT_GT(orders_seen & ~1, 0) << "the smooth phase uses a higher order";
  EXPECT_NE(orders_seen & 1, 0) << "the jerky phase falls back to order 0";
}

TEST(IncrementExtrapolationTest, AlternatingIncrementsRepeatTheLastOne) {
  IncrementExtrapolation e;
  const Eigen::Vector3d v(1.0, -2.0, 0.5);
  for (int k = 0; k < 8; ++k) e.Push((k % 2 ? -1.0 : 1.0) * v);
  EXPECT_EQ(e.order(), 0);  // the miss of order p is 2^(p+1) |v|
  Eigen::VectorXd guess;
  e.Predict(3, guess);
  EXPECT_EQ(guess, Eigen::VectorXd(-v));
}

TEST(IncrementExtrapolationTest, ClearAndSizeChangeRestart) {
  IncrementExtrapolation e;
  Eigen::VectorXd guess;
  e.Predict(4, guess);
  EXPECT_EQ(guess, Eigen::VectorXd::Zero(4));
  EXPECT_EQ(e.order(), -1);
  for (int k = 0; k < 6; ++k) e.Push(Eigen::VectorXd::Constant(4, k));
  e.Clear();
  EXPECT_EQ(e.history(), 0);
  e.Predict(4, guess);
  EXPECT_EQ(guess, Eigen::VectorXd::Zero(4));
  e.Push(Eigen::VectorXd::Constant(4, 2.0));
  e.Push(Eigen::VectorXd::Constant(6, 1.0));  // another body size: only this one counts
  EXPECT_EQ(e.history(), 1);
  e.Predict(6, guess);
  EXPECT_EQ(guess, Eigen::VectorXd::Constant(6, 1.0));
  e.Predict(4, guess);  // asked for another size: no prediction
  EXPECT_EQ(guess, Eigen::VectorXd::Zero(4));
}

}  // namespace
}  // namespace vesica::physics
