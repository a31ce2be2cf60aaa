#pragma once
// An exact solve on a few nodes of the system S x = r, for the rotated-factor preconditioner.
// The rest factor turned per node is a near-exact inverse where a node's tets turn together and a
// poor one where they turn apart: around a grasped node or a sharp bend. There the preconditioned
// operator's extreme eigenvalues live (0.53 and 1.95 on the 2,900-node gallbladder box, their
// eigenvectors 90 % on ~50 nodes around the pulled one), and PCG gains a decade an iteration. A
// dense Cholesky of S restricted to those nodes, applied before and after the factor, removes
// them: 8.3 -> 5.9 iterations with 48 nodes (docs/performance/fem.md, round 7).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "physics/fem/sparse_pattern.h"

namespace vesica::physics {

class LocalBlockCorrection {
 public:
  /// Takes S_PP, the rows and columns of `values` (on `pattern`) of the given nodes' dofs, and
  /// factorises it. Returns false, and leaves the correction empty, when S_PP is not positive
  /// definite. An empty node list leaves it empty (Apply does nothing).
  bool Compute(const SparsePattern& pattern, const Eigen::VectorXd& values, const std::vector<int>& nodes);
  void Clear();
  bool empty() const { return dofs_.empty(); }
  const std::vector<int>& dofs() const { return dofs_; }

  /// r is the residual of z (r = b - S z): z_P += S_PP^-1 r_P and r -= S(:, P) of that, so that r
  /// stays z's residual (and is 0 on P after).
  void Apply(Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  /// The same from the residual r of z - c, for c just added to z: the correction needs r - S c on
  /// P only (rows P of S times c), so r is left as it is.
  void ApplyAfter(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& z) const;

 private:
  const SparsePattern* pattern_ = nullptr;
  const Eigen::VectorXd* values_ = nullptr;
  std::vector<int> dofs_;  // P's dofs, node by node
  Eigen::LLT<Eigen::MatrixXd> factor_;
  mutable Eigen::VectorXd local_;  // scratch: r_P, then the correction
};

/// The `count` nodes with the largest `spread` (count >= spread.size(): all), largest first; nodes
/// whose spread is 0 are left out.
std::vector<int> LargestSpreadNodes(const std::vector<double>& spread, int count);

}  // namespace vesica::physics
