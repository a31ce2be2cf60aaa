#include "physics/fem/increment_extrapolation.h"

#include <algorithm>

namespace vesica::physics {

void IncrementExtrapolation::Clear() {
  count_ = 0;
  order_ = -1;
}

void IncrementExtrapolation::Push(const Eigen::VectorXd& increment) {
  constexpr int kLevels = kMaxOrder + 2;
  if (count_ > 0 && differences_[0].size() != increment.size()) Clear();
  if (differences_.size() != kLevels) differences_.resize(kLevels);
  // D'_0 = du, D'_k = D'_{k-1} - D_{k-1} (old); D'_{p+1} is how far the order-p prediction missed
  // du. `scratch_` carries the old D_{k-1} up the table (swaps, no allocation after the first step).
  const int levels = std::min(count_ + 1, kLevels);
  scratch_ = differences_[0];
  differences_[0] = increment;
  int best_order = 0;
  double best_error = -1.0;
  for (int k = 1; k < levels; ++k) {
    differences_[k].swap(scratch_);                             // D_k <- old D_{k-1}, scratch <- old D_k
    differences_[k] = differences_[k - 1] - differences_[k];  // coefficient-wise: no aliasing
    const double error = differences_[k].squaredNorm();
    if (best_error < 0.0 || error < best_error) best_error = error, best_order = k - 1;
  }
  count_ = levels;
  order_ = count_ >= 2 ? best_order : 0;
}

void IncrementExtrapolation::Predict(Eigen::Index size, Eigen::VectorXd& guess) const {
  if (count_ == 0 || differences_[0].size() != size) {
    guess.setZero(size);
    return;
  }
  guess = differences_[0];
  for (int k = 1; k <= order_; ++k) guess += differences_[k];
}

}  // namespace vesica::physics
