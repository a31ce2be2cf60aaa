#pragma once
// Warm start of an implicit step's solve: the next displacement increment du predicted from the
// last ones by polynomial extrapolation, of the order that predicted the latest increment best.

#include <vector>

#include <Eigen/Core>

namespace vesica::physics {

/// Keeps the backward differences D_k = nabla^k du_n (k = 0..kMaxOrder + 1) of the accepted
/// increments. The order-p prediction of du_{n+1} is D_0 + D_1 + ... + D_p (Newton's backward
/// formula: exact when the increments lie on a polynomial of degree p in the step index; p = 1 is
/// 2 du_n - du_{n-1}); its error on du_{n+1} would be nabla^{p+1} du_{n+1}. After each increment
/// the order whose prediction of it missed least (Euclidean norm) is kept for the next one: a
/// smoothly moving body gets the high orders, a jerky one the low ones (higher orders amplify
/// noise: order p multiplies it by up to 2^(p+1) - 1).
class IncrementExtrapolation {
 public:
  static constexpr int kMaxOrder = 4;

  /// Records an accepted increment (3n). A size change restarts the history.
  void Push(const Eigen::VectorXd& increment);
  /// Forgets every increment (after a rejected step or an unrelated solve).
  void Clear();
  /// Number of increments recorded since the last Clear (saturates at kMaxOrder + 2).
  int history() const { return count_; }
  /// Order of the next prediction: -1 without history, else 0..kMaxOrder.
  int order() const { return order_; }
  /// Writes the prediction of the next increment; zeros of size `size` without history.
  void Predict(Eigen::Index size, Eigen::VectorXd& guess) const;

 private:
  std::vector<Eigen::VectorXd> differences_;  // D_0..D_{kMaxOrder+1}; D_k valid for k < count_
  Eigen::VectorXd scratch_;
  int count_ = 0;
  int order_ = -1;
};

}  // namespace vesica::physics
