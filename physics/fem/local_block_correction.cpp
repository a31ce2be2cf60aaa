#include "physics/fem/local_block_correction.h"

#include <algorithm>

namespace vesica::physics {

bool LocalBlockCorrection::Compute(const SparsePattern& pattern, const Eigen::VectorXd& values,
                                   const std::vector<int>& nodes) {
  Clear();
  if (nodes.empty()) return true;
  const Eigen::SparseMatrix<double>& structure = pattern.structure;
  std::vector<int> local_index(static_cast<size_t>(structure.cols()), -1);
  std::vector<int> dofs;
  dofs.reserve(3 * nodes.size());
  for (int n : nodes)
    for (int d = 0; d < 3; ++d) {
      local_index[3 * n + d] = static_cast<int>(dofs.size());
      dofs.push_back(3 * n + d);
    }
  const int size = static_cast<int>(dofs.size());
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(size, size);
  const int* begin = structure.outerIndexPtr();
  const int* row = structure.innerIndexPtr();
  for (int a = 0; a < size; ++a)
    for (int k = begin[dofs[a]]; k < begin[dofs[a] + 1]; ++k)
      if (const int b = local_index[row[k]]; b >= 0) block(b, a) = values[k];
  factor_.compute(block);
  if (factor_.info() != Eigen::Success) return false;
  pattern_ = &pattern;
  values_ = &values;
  dofs_ = std::move(dofs);
  return true;
}

void LocalBlockCorrection::Clear() {
  dofs_.clear();
  pattern_ = nullptr;
  values_ = nullptr;
}

void LocalBlockCorrection::Apply(Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if (empty()) return;
  const int size = static_cast<int>(dofs_.size());
  local_.resize(size);
  for (int a = 0; a < size; ++a) local_[a] = r[dofs_[a]];
  factor_.solveInPlace(local_);
  const int* begin = pattern_->structure.outerIndexPtr();
  const int* row = pattern_->structure.innerIndexPtr();
  const double* value = values_->data();
  for (int a = 0; a < size; ++a) {
    const int j = dofs_[a];
    const double delta = local_[a];
    z[j] += delta;
    for (int k = begin[j]; k < begin[j + 1]; ++k) r[row[k]] -= value[k] * delta;
  }
}

void LocalBlockCorrection::ApplyAfter(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& z) const {
  if (empty()) return;
  const int size = static_cast<int>(dofs_.size());
  local_.resize(size);
  const int* begin = pattern_->structure.outerIndexPtr();
  const int* row = pattern_->structure.innerIndexPtr();
  const double* value = values_->data();
  for (int a = 0; a < size; ++a) {
    const int j = dofs_[a];
    double s_c = 0.0;  // (S c)_j: column j of the symmetric S is its row j
    for (int k = begin[j]; k < begin[j + 1]; ++k) s_c += value[k] * c[row[k]];
    local_[a] = r[j] - s_c;
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
