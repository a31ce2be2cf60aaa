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
#include <functional>
#include <vector>

#include "physics/fem/sparse_pattern.h"

namespace vesica::physics {

/// Appends row `dof` of a symmetric matrix to `columns` and `values` (any order, no repeats).
using SymmetricRowSource = std::function<void(int dof, std::vector<int>& columns, std::vector<double>& values)>;

class LocalBlockCorrection {
 public:
  /// Copies the rows of the given nodes' dofs (S(P, :), which the corrections need; by symmetry
  /// also the columns), factorises S_PP and keeps both: nothing refers back to S afterwards.
  /// Returns false, and leaves the correction empty, when S_PP is not positive definite. An empty
  /// node list leaves it empty (Apply does nothing). `num_dofs`: S's size.
  bool Compute(int num_dofs, const SymmetricRowSource& rows, const std::vector<int>& nodes);
  /// The same from `values` on `pattern` (rows read as the symmetric columns).
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
  std::vector<int> dofs_;  // P's dofs, node by node
  // Row a of S(P, :) (dof dofs_[a]): entries [row_begin_[a], row_begin_[a + 1]) of row_column_ / row_value_.
  std::vector<int> row_begin_, row_column_;
  std::vector<double> row_value_;
  Eigen::LLT<Eigen::MatrixXd> factor_;
  mutable Eigen::VectorXd local_;  // scratch: r_P, then the correction
};

/// The `count` nodes with the largest `spread` (count >= spread.size(): all), largest first; nodes
/// whose spread is 0 are left out.
std::vector<int> LargestSpreadNodes(const std::vector<double>& spread, int count);

}  // namespace vesica::physics
