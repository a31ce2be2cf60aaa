#include "physics/fem/local_block_correction.h"

#include <algorithm>

namespace vesica::physics {

bool LocalBlockCorrection::Compute(int num_dofs, const SymmetricRowSource& rows, const std::vector<int>& nodes) {
  Clear();
  if (nodes.empty()) return true;
  std::vector<int> local_index(static_cast<size_t>(num_dofs), -1);
  std::vector<int> dofs;
  dofs.reserve(3 * nodes.size());
  for (int n : nodes)
    for (int d = 0; d < 3; ++d) {
      local_index[3 * n + d] = static_cast<int>(dofs.size());
      dofs.push_back(3 * n + d);
    }
  const int size = static_cast<int>(dofs.size());
  row_begin_.assign(1, 0);
  for (int a = 0; a < size; ++a) {
    rows(dofs[a], row_column_, row_value_);
    row_begin_.push_back(static_cast<int>(row_column_.size()));
  }
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(size, size);
  for (int a = 0; a < size; ++a)
    for (int k = row_begin_[a]; k < row_begin_[a + 1]; ++k)
      if (const int b = local_index[row_column_[k]]; b >= 0) block(a, b) = row_value_[k];
  factor_.compute(block);
  if (factor_.info() != Eigen::Success) {
    Clear();
    return false;
  }
  dofs_ = std::move(dofs);
  return true;
}

bool LocalBlockCorrection::Compute(const SparsePattern& pattern, const Eigen::VectorXd& values,
                                   const std::vector<int>& nodes) {
  const Eigen::SparseMatrix<double>& structure = pattern.structure;
  const int* begin = structure.outerIndexPtr();
  const int* row = structure.innerIndexPtr();
  return Compute(
      static_cast<int>(structure.cols()),
      [&](int dof, std::vector<int>& columns, std::vector<double>& row_values) {
        for (int k = begin[dof]; k < begin[dof + 1]; ++k) {  // column dof of the symmetric S is its row
          columns.push_back(row[k]);
          row_values.push_back(values[k]);
        }
      },
      nodes);
}

void LocalBlockCorrection::Clear() {
  dofs_.clear();
  row_begin_.clear();
  row_column_.clear();
  row_value_.clear();
}

void LocalBlockCorrection::Apply(Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if (empty()) return;
  const int size = static_cast<int>(dofs_.size());
  local_.resize(size);
  for (int a = 0; a < size; ++a) local_[a] = r[dofs_[a]];
  factor_.solveInPlace(local_);
  for (int a = 0; a < size; ++a) {
    const double delta = local_[a];
    z[dofs_[a]] += delta;
    for (int k = row_begin_[a]; k < row_begin_[a + 1]; ++k) r[row_column_[k]] -= row_value_[k] * delta;
  }
}

void LocalBlockCorrection::ApplyAfter(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& z) const {
  if (empty()) return;
  const int size = static_cast<int>(dofs_.size());
  local_.resize(size);
  for (int a = 0; a < size; ++a) {
    double s_c = 0.0;  // (S c)_j, j = dofs_[a]
    for (int k = row_begin_[a]; k < row_begin_[a + 1]; ++k) s_c += row_value_[k] * c[row_column_[k]];
    local_[a] = r[dofs_[a]] - s_c;
  }
  factor_.solveInPlace(local_);
  for (int a = 0; a < size; ++a) z[dofs_[a]] += local_[a];
}

std::vector<int> LargestSpreadNodes(const std::vector<double>& spread, int count) {
  std::vector<int> nodes;
  for (int n = 0; n < static_cast<int>(spread.size()); ++n)
    if (spread[n] > 0.0) nodes.push_back(n);
  // Largest first, ties by node index: the same nodes on every run.
  auto larger = [&](int a, int b) { return spread[a] > spread[b] || (spread[a] == spread[b] && a < b); };
  if (count < static_cast<int>(nodes.size())) {
    std::nth_element(nodes.begin(), nodes.begin() + count, nodes.end(), larger);
    nodes.resize(std::max(count, 0));
  }
  std::sort(nodes.begin(), nodes.end(), larger);
  return nodes;
}

}  // namespace vesica::physics
