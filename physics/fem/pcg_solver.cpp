#include "physics/fem/pcg_solver.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "physics/fem/block_rows_simd.h"
#include "physics/fem/elastic_forces.h"

namespace vesica::physics {

void BlockJacobiPreconditioner::Compute(const SparsePattern& p, const Eigen::VectorXd& values) {
  const int nodes = static_cast<int>(p.structure.cols()) / 3;
  inverse_blocks_.resize(nodes);
  for (int i = 0; i < nodes; ++i) {
    Eigen::Matrix3d block;
    const int diag = p.diagonal_slot[3 * i];  // entry (3i, 3i); block columns are stride apart
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) block(r, c) = values[diag + c * p.column_stride[i] + r];
    inverse_blocks_[i] = block.inverse();
  }
}

void BlockJacobiPreconditioner::Compute(const FloatBlockRows& rows) {
  inverse_blocks_.resize(rows.nodes_);
  for (int i = 0; i < rows.nodes_; ++i) {
    const float* v = rows.values_.data() + 9 * static_cast<size_t>(rows.diagonal_block_[i]);
    Eigen::Matrix3d block;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) block(r, c) = v[3 * r + c];
    inverse_blocks_[i] = block.inverse();
  }
}

void BlockJacobiPreconditioner::Apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  for (size_t i = 0; i < inverse_blocks_.size(); ++i) z.segment<3>(3 * i) = inverse_blocks_[i] * r.segment<3>(3 * i);
}

namespace {
BlockRowsView RowsOf(const SparsePattern& p, const Eigen::VectorXd& values, int nodes) {
  BlockRowsView view;
  view.nodes = nodes;
  view.outer = p.structure.outerIndexPtr();
  view.inner = p.structure.innerIndexPtr();
  view.column_stride = p.column_stride.data();
  view.diagonal_slot = p.diagonal_slot.data();
  view.values = values.data();
  return view;
}

double* SweepScratch(int nodes) {
  thread_local std::vector<double> scratch;
  if (static_cast<int>(scratch.size()) < BlockRowSweepScratch(nodes)) scratch.resize(BlockRowSweepScratch(nodes));
  return scratch.data();
}

// Adds the products of row i's off-diagonal blocks in slots [begin, end) of its columns with x to
// (s0, s1, s2) (row i of the symmetric matrix is column i: gather form).
inline void GatherBlocks(const double* v, const int* inner, const double* x, int begin, int end, int stride,
                         double& s0, double& s1, double& s2) {
  for (int k = begin; k < end; k += 3) {
    const double* xa = x + inner[k];
    const double* c0 = v + k;
    const double* c1 = c0 + stride;
    const double* c2 = c1 + stride;
    s0 += c0[0] * xa[0] + c0[1] * xa[1] + c0[2] * xa[2];
    s1 += c1[0] * xa[0] + c1[1] * xa[1] + c1[2] * xa[2];
    s2 += c2[0] * xa[0] + c2[1] * xa[1] + c2[2] * xa[2];
  }
}
}  // namespace

void BlockGaussSeidelSweep(const SparsePattern& p, const Eigen::VectorXd& values,
                           const std::vector<Eigen::Matrix3d>& inverse_diagonal, const Eigen::VectorXd& b,
                           Eigen::VectorXd& x, bool forward) {
  const int nodes = static_cast<int>(inverse_diagonal.size());
  if (BlockRowKernelsUseAvx2()) {
    BlockGaussSeidelSweepAvx2(RowsOf(p, values, nodes), inverse_diagonal.data()->data(), b.data(), x.data(), forward,
                              SweepScratch(nodes));
    return;
  }
  const int* outer = p.structure.outerIndexPtr();
  const int* inner = p.structure.innerIndexPtr();
  const double* v = values.data();
  double* xs = x.data();
  for (int step = 0; step < nodes; ++step) {
    const int i = forward ? step : nodes - 1 - step;
    const int begin = outer[3 * i], stride = p.column_stride[i];
    const int diagonal = p.diagonal_slot[3 * i];  // rows are sorted: blocks before it are j < i
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    GatherBlocks(v, inner, xs, begin, diagonal, stride, s0, s1, s2);
    GatherBlocks(v, inner, xs, diagonal + 3, begin + stride, stride, s0, s1, s2);
    const Eigen::Vector3d t(b[3 * i] - s0, b[3 * i + 1] - s1, b[3 * i + 2] - s2);
    x.segment<3>(3 * i) = inverse_diagonal[i] * t;
  }
}

void ForwardSweepFromZeroAndUpperTimes(const SparsePattern& p, const Eigen::VectorXd& values,
                                       const std::vector<Eigen::Matrix3d>& inverse_diagonal, const Eigen::VectorXd& b,
                                       Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const int nodes = static_cast<int>(inverse_diagonal.size());
  const int* outer = p.structure.outerIndexPtr();
  const int* inner = p.structure.innerIndexPtr();
  const double* v = values.data();
  x.setZero(3 * nodes);
  y.setZero(3 * nodes);
  if (BlockRowKernelsUseAvx2()) {
    ForwardSweepFromZeroAndUpperTimesAvx2(RowsOf(p, values, nodes), inverse_diagonal.data()->data(), b.data(),
                                          x.data(), y.data(), SweepScratch(nodes));
    return;
  }
  double* xs = x.data();
  double* ys = y.data();
  for (int i = 0; i < nodes; ++i) {
    const int begin = outer[3 * i], stride = p.column_stride[i];
    const int diagonal = p.diagonal_slot[3 * i];  // blocks before it: rows of nodes j < i
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    GatherBlocks(v, inner, xs, begin, diagonal, stride, s0, s1, s2);  // x_j = 0 for j > i
    const Eigen::Vector3d xi = inverse_diagonal[i] * Eigen::Vector3d(b[3 * i] - s0, b[3 * i + 1] - s1, b[3 * i + 2] - s2);
    xs[3 * i] = xi[0], xs[3 * i + 1] = xi[1], xs[3 * i + 2] = xi[2];
    for (int k = begin; k < diagonal; k += 3) {  // block A_ji, rows 3j..3j+2 of column block i
      double* yj = ys + inner[k];
      const double* c0 = v + k;
      const double* c1 = c0 + stride;
      const double* c2 = c1 + stride;
      yj[0] += c0[0] * xi[0] + c1[0] * xi[1] + c2[0] * xi[2];
      yj[1] += c0[1] * xi[0] + c1[1] * xi[1] + c2[1] * xi[2];
      yj[2] += c0[2] * xi[0] + c1[2] * xi[1] + c2[2] * xi[2];
    }
  }
}

void UpperBlocksTimes(const SparsePattern& p, const Eigen::VectorXd& values, const Eigen::VectorXd& x,
                      Eigen::VectorXd& y) {
  const int nodes = static_cast<int>(p.structure.cols()) / 3;
  const int* outer = p.structure.outerIndexPtr();
  const int* inner = p.structure.innerIndexPtr();
  y.resize(3 * nodes);
  for (int i = 0; i < nodes; ++i) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    GatherBlocks(values.data(), inner, x.data(), p.diagonal_slot[3 * i] + 3, outer[3 * i] + p.column_stride[i],
                 p.column_stride[i], s0, s1, s2);
    y[3 * i] = s0;
    y[3 * i + 1] = s1;
    y[3 * i + 2] = s2;
  }
}

bool FloatBlockRows::available() { return BlockRowKernelsUseAvx2(); }

void FloatBlockRows::Reshape(const SparsePattern& p) {
  const int nodes = static_cast<int>(p.structure.cols()) / 3;
  const int* outer = p.structure.outerIndexPtr();
  const int* inner = p.structure.innerIndexPtr();
  if (nodes != nodes_ || p.structure.nonZeros() != nonzeros_) {
    nodes_ = nodes;
    nonzeros_ = p.structure.nonZeros();
    row_begin_.assign(1, 0);
    diagonal_block_.resize(nodes);
    column_.clear();
    source_.clear();
    source_stride_.clear();
    for (int i = 0; i < nodes; ++i) {
      const int begin = outer[3 * i], stride = p.column_stride[i];
      for (int k = begin; k < begin + stride; k += 3) {  // rows 3j..3j+2 of column 3i, j ascending
        if (inner[k] == 3 * i) diagonal_block_[i] = static_cast<int>(column_.size());
        column_.push_back(inner[k] / 3);
        source_.push_back(k);
        source_stride_.push_back(stride);
      }
      row_begin_.push_back(static_cast<int>(column_.size()));
    }
    values_.assign(9 * column_.size() + 4, 0.0f);
  }
}

std::vector<int> FloatBlockRows::ValueIndexOfSlots(const SparsePattern& p) const {
  std::vector<int> index(static_cast<size_t>(p.structure.nonZeros()), -1);
  for (size_t k = 0; k < column_.size(); ++k)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) index[source_[k] + r * source_stride_[k] + c] = static_cast<int>(9 * k) + 3 * r + c;
  return index;
}

void FloatBlockRows::AppendRow(int dof, std::vector<int>& columns, std::vector<double>& values) const {
  const int i = dof / 3, r = dof % 3;
  for (int k = row_begin_[i]; k < row_begin_[i + 1]; ++k)
    for (int c = 0; c < 3; ++c) {
      columns.push_back(3 * column_[k] + c);
      values.push_back(values_[9 * k + 3 * r + c]);
    }
}

void FloatBlockRows::Update(const SparsePattern& p, const Eigen::VectorXd& values) {
  Reshape(p);
  // Row r of block (i, j) is A(3i + r, 3j..3j+2) = A(3j..3j+2, 3i + r): column 3i + r's triplet.
  const double* v = values.data();
  float* out = values_.data();
  for (size_t k = 0; k < column_.size(); ++k) {
    const double* c0 = v + source_[k];
    const int stride = source_stride_[k];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out[9 * k + 3 * r + c] = static_cast<float>(c0[r * stride + c]);
  }
}

namespace {
FloatBlockRowsView RowsOf(const FloatBlockRows& rows, const std::vector<int>& row_begin,
                          const std::vector<int>& diagonal_block, const HugePageVector<int>& column,
                          const HugePageVector<float>& values) {
  FloatBlockRowsView view;
  view.nodes = rows.nodes();
  view.row_begin = row_begin.data();
  view.diagonal_block = diagonal_block.data();
  view.column = column.data();
  view.values = values.data();
  return view;
}
}  // namespace

void BlockGaussSeidelSweep(const FloatBlockRows& rows, const std::vector<Eigen::Matrix3d>& inverse_diagonal,
                           const Eigen::VectorXd& b, Eigen::VectorXd& x, bool forward) {
  const int nodes = rows.nodes_;
  FloatBlockGaussSeidelSweepAvx2(RowsOf(rows, rows.row_begin_, rows.diagonal_block_, rows.column_, rows.values_),
                                 inverse_diagonal.data()->data(), b.data(), x.data(), forward, SweepScratch(nodes));
}

void ForwardSweepFromZeroAndUpperTimes(const FloatBlockRows& rows, const std::vector<Eigen::Matrix3d>& inverse_diagonal,
                                       const Eigen::VectorXd& b, Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const int nodes = rows.nodes_;
  x.resize(3 * nodes);
  y.resize(3 * nodes);
  FloatForwardSweepFromZeroAndUpperTimesAvx2(RowsOf(rows, rows.row_begin_, rows.diagonal_block_, rows.column_, rows.values_),
                                             inverse_diagonal.data()->data(), b.data(), x.data(), y.data(),
                                             SweepScratch(nodes));
}

PcgResult SolvePcg(const MatrixOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                   const Preconditioner& preconditioner, double relative_tolerance, int max_iterations,
                   const Eigen::VectorXd* initial_product, Eigen::VectorXd* final_product) {
  PcgResult result;
  const double b_norm = b.norm();
  if (!std::isfinite(b_norm)) {  // every residual test would pass against an infinite target
    result.relative_residual = std::numeric_limits<double>::quiet_NaN();
    result.breakdown = true;
    return result;
  }
  if (b_norm == 0.0) {
    x.setZero(b.size());
    if (final_product) final_product->setZero(b.size());
    result.converged = true;
    return result;
  }
  Eigen::VectorXd r(b.size()), z, p, q;
  if (x.size() == b.size() && initial_product && initial_product->size() == b.size()) {
    r = b - *initial_product;
  } else {
    if (x.size() != b.size()) x.setZero(b.size());
    apply(x, q);
    r = b - q;
  }
  const double target = relative_tolerance * b_norm;
  double r_norm = r.norm();
  if (r_norm <= target) {
    result.relative_residual = r_norm / b_norm;
    result.converged = true;
    if (final_product) *final_product = b - r;
    return result;
  }
  preconditioner(r, z);
  double rz = r.dot(z);
  p.swap(z);  // p = z: z is written again before it is read
  std::array<double, kPcgSpectrumIterations> alphas, betas;
  int lanczos_steps = 0;
  for (int it = 1; it <= max_iterations; ++it) {
    apply(p, q);
    const double pq = p.dot(q);
    if (!(pq > 0.0)) {  // stop; p.A p < 0 (not positive definite) or NaN is a breakdown, while
      // p.A p = 0 is p underflowing on a residual far below any tolerance: x is as good as it gets
      result.breakdown = !(pq == 0.0);
      break;
    }
    const double alpha = rz / pq;
    if (lanczos_steps < kPcgSpectrumIterations) alphas[lanczos_steps++] = alpha;
    x += alpha * p;
    r -= alpha * q;
    result.iterations = it;
    r_norm = r.norm();
    if (r_norm <= target || it == max_iterations) break;  // capped: no application for nothing
    preconditioner(r, z);
    const double rz_next = r.dot(z);
    if (lanczos_steps <= kPcgSpectrumIterations - 1) betas[lanczos_steps - 1] = rz_next / rz;
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  result.relative_residual = r_norm / b_norm;
  result.converged = r_norm <= target;
  result.spectrum = EstimateSpectrumFromCg(std::span(alphas.data(), lanczos_steps),
                                           std::span(betas.data(), std::max(lanczos_steps - 1, 0)));
  if (final_product) *final_product = b - r;
  return result;
}

PcgResult SolvePcg(const SparsePattern& pattern, const Eigen::VectorXd& values, const Eigen::VectorXd& b,
                   Eigen::VectorXd& x, const Preconditioner& preconditioner, double relative_tolerance,
                   int max_iterations) {
  return SolvePcg([&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { SymmetricPatternMultiply(pattern, values, in, out); },
                  b, x, preconditioner, relative_tolerance, max_iterations);
}

}  // namespace vesica::physics
