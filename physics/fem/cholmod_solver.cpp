#include "physics/fem/cholmod_solver.h"

#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "physics/fem/half_factor.h"
#include "physics/fem/huge_page_allocator.h"

namespace vesica::physics {

namespace {

using Decomposition = Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower>;

// Eigen keeps CHOLMOD's factor protected; the float copy needs its supernodes.
struct FactorAccess : Decomposition {
  static const cholmod_factor* Of(const Decomposition& d) {
    return static_cast<const FactorAccess&>(d).m_cholmodFactor;
  }
};

// CHOLMOD 5.12 runs small loops of its supernodal factorisation in OpenMP regions of a fixed 4
// threads (CHOLMOD_OMP_NUM_THREADS, compiled in: OMP_NUM_THREADS does not change it). On the 2-core
// machine their fork and join cost 4x the factorisation (45 instead of 10 ms at 980 nodes). While
// it lives, the calling thread's OpenMP regions are inactive (max active levels 0, a per-thread
// setting), so CHOLMOD runs them serially; the previous level comes back after. Looked up at run
// time: the OpenMP runtime is CHOLMOD's dependency, not ours, and a build without one needs nothing.
class SerialCholmodRegions {
 public:
  SerialCholmodRegions() {
    if (set_ && get_) {
      previous_ = get_();
      set_(0);
    }
  }
  ~SerialCholmodRegions() {
    if (set_ && get_) set_(previous_);
  }
  SerialCholmodRegions(const SerialCholmodRegions&) = delete;
  SerialCholmodRegions& operator=(const SerialCholmodRegions&) = delete;

 private:
  using SetLevels = void (*)(int);
  using GetLevels = int (*)();
  inline static const SetLevels set_ = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  inline static const GetLevels get_ = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  int previous_ = 0;
};

// CHOLMOD stops an L L^T factorisation at the first non-positive pivot (minor < n), but its
// simplicial L D L^T accepts negative entries of D: check those (first entry of each column).
bool PositiveDefinite(const cholmod_factor& l) {
  if (l.minor < l.n) return false;
  if (l.is_super || l.is_ll) return true;
  const int* p = static_cast<const int*>(l.p);
  const double* x = static_cast<const double*>(l.x);
  for (size_t j = 0; j < l.n; ++j)
    if (!(x[p[j]] > 0.0)) return false;
  return true;
}

// LAPACK's triangular inverse and BLAS's triangular product in single precision (the Fortran
// interface, which the BLAS CHOLMOD uses provides; the trailing lengths are the hidden string
// lengths).
extern "C" {
void strtri_(const char* uplo, const char* diag, const int* n, float* a, const int* lda, int* info, std::size_t,
             std::size_t);
void strmm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const float* alpha, const float* a, const int* lda, float* b, const int* ldb, std::size_t, std::size_t,
            std::size_t, std::size_t);
}

// One supernode's [L_D; L_B] (nr x nc, column-major) as [L_D^-1; L_B L_D^-1] (half_factor.h) in
// `out`, computed in float: it is rounded to half next, and float's error (~6e-8 of L_D's condition
// number) stays below half's; twice as fast as double. False when the triangle is singular or an
// entry is not finite.
bool PartitionedInverse(const double* block, int nr, int nc, std::vector<float>& out) {
  out.resize(static_cast<std::size_t>(nr) * nc);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = static_cast<float>(block[k]);
  int info = 0;
  strtri_("L", "N", &nc, out.data(), &nr, &info, 1, 1);
  if (info != 0) return false;
  const int below = nr - nc;
  const float one = 1.0f;
  if (below > 0) strmm_("R", "L", "N", "N", &below, &nc, &one, out.data(), &nr, out.data() + nc, &nr, 1, 1, 1, 1);
  for (float v : out)
    if (!std::isfinite(v)) return false;
  return true;
}

// The power of two that brings `largest` near 2^14 (binary16 tops out at 65504).
double HalfScale(double largest) { return largest > 0.0 ? std::exp2(std::floor(std::log2(16384.0 / largest))) : 1.0; }

// Supernodal L L^T = P A P^T with L rounded to float, or as its partitioned inverse in half
// (half_factor.h). Supernode s holds columns [super[s], super[s+1]) as a dense column-major block
// of pi[s+1] - pi[s] rows (row indices rows[pi[s]...], the first ones its own columns) starting at
// values[px[s]].
struct SingleFactor {
  std::vector<int> super, pi, px, rows, perm;
  std::vector<int> position;  // inverse of perm: entry j of b is y[position[j]]
  HugePageVector<float> values;
  HugePageVector<std::uint16_t> half_values;
  std::vector<std::size_t> half_px;  // supernode starts in half_values
  std::vector<float> unscales;       // HalfFactorView::unscales
  bool half = false;
  mutable Eigen::VectorXf y, gathered;

  // The half copy: each supernode's partitioned inverse in tiles, T and W scaled by powers of two
  // of their own. False (nothing usable kept) when some supernode has no finite inverse.
  bool CopyHalf(const cholmod_factor& l) {
    const int ns = static_cast<int>(l.nsuper);
    const double* x = static_cast<const double*>(l.x);
    half_px.resize(ns + 1);
    half_px[0] = 0;
    for (int s = 0; s < ns; ++s)
      half_px[s + 1] = half_px[s] + TiledSupernodeEntries(pi[s + 1] - pi[s], super[s + 1] - super[s]);
    half_values.resize(half_px[ns]);
    unscales.resize(2 * static_cast<std::size_t>(ns));
    std::vector<float> inverse;
    for (int s = 0; s < ns; ++s) {
      const int nr = pi[s + 1] - pi[s], nc = super[s + 1] - super[s];
      if (!PartitionedInverse(x + px[s], nr, nc, inverse)) return false;
      double largest_t = 0.0, largest_w = 0.0;
      for (int j = 0; j < nc; ++j) {
        const float* column = inverse.data() + static_cast<std::ptrdiff_t>(j) * nr;
        for (int i = j; i < nc; ++i) largest_t = std::max(largest_t, static_cast<double>(std::abs(column[i])));
        for (int i = nc; i < nr; ++i) largest_w = std::max(largest_w, static_cast<double>(std::abs(column[i])));
      }
      const double triangle_scale = HalfScale(largest_t), below_scale = HalfScale(largest_w);
      WriteTiledSupernodeF16c(inverse.data(), nr, nc, triangle_scale, below_scale, half_values.data() + half_px[s]);
      unscales[2 * s] = static_cast<float>(1.0 / triangle_scale);
      unscales[2 * s + 1] = static_cast<float>(1.0 / below_scale);
    }
    return true;
  }

  bool CopyFrom(const cholmod_factor& l, bool half_storage) {
    if (!l.is_super || !l.is_ll || l.xtype != CHOLMOD_REAL || l.itype != CHOLMOD_INT) return false;
    const int n = static_cast<int>(l.n), ns = static_cast<int>(l.nsuper);
    const int* super_in = static_cast<const int*>(l.super);
    const int* pi_in = static_cast<const int*>(l.pi);
    const int* px_in = static_cast<const int*>(l.px);
    super.assign(super_in, super_in + ns + 1);
    pi.assign(pi_in, pi_in + ns + 1);
    px.assign(px_in, px_in + ns + 1);
    rows.assign(static_cast<const int*>(l.s), static_cast<const int*>(l.s) + pi[ns]);
    perm.assign(static_cast<const int*>(l.Perm), static_cast<const int*>(l.Perm) + n);
    position.resize(n);
    for (int k = 0; k < n; ++k) position[perm[k]] = k;
    half = half_storage && HalfFactorSupported() && CopyHalf(l);
    if (!half) {
      const double* x = static_cast<const double*>(l.x);
      values.resize(px[ns]);
      for (size_t k = 0; k < values.size(); ++k) values[k] = static_cast<float>(x[k]);
      half_values.clear();
      half_px.clear();
      unscales.clear();
    } else {
      values.clear();
    }
    y.resize(n);
    int widest = 0;
    for (int s = 0; s < ns; ++s) widest = std::max(widest, pi[s + 1] - pi[s]);
    gathered.setZero(widest + kHalfFactorPadding);  // the kernels read (and add zeros to) a vector past nr
    return true;
  }

  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    const int n = static_cast<int>(perm.size());
    for (int k = 0; k < n; ++k) y[k] = static_cast<float>(b[perm[k]]);
    SolveInPlace();
    x.resize(n);
    for (int k = 0; k < n; ++k) x[perm[k]] = static_cast<double>(y[k]);
  }

  // x = R (L L^T)^-1 R^T b for R block diagonal (rotations[i] on rows 3i..3i+2): each node's 3
  // entries turned on their way into the factor's order and out of it, with no turned vectors
  // stored (the same values as turning, solving and turning back).
  void SolveTurned(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    const int n = static_cast<int>(perm.size()), nodes = n / 3;
    for (int i = 0; i < nodes; ++i) {
      const Eigen::Vector3d turned = rotations[i].transpose() * b.segment<3>(3 * i);
      for (int c = 0; c < 3; ++c) y[position[3 * i + c]] = static_cast<float>(turned[c]);
    }
    SolveInPlace();
    x.resize(n);
    for (int i = 0; i < nodes; ++i) {
      Eigen::Vector3d solved;
      for (int c = 0; c < 3; ++c) solved[c] = static_cast<double>(y[position[3 * i + c]]);
      x.segment<3>(3 * i) = rotations[i] * solved;
    }
  }

  // y <- (L L^T)^-1 y with the stored factor.
  void SolveInPlace() const {
    using Block = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;
    const int ns = static_cast<int>(super.size()) - 1;
    if (half) {
      HalfFactorView view;
      view.super = super.data(), view.pi = pi.data(), view.px = half_px.data(), view.rows = rows.data();
      view.num_supernodes = ns;
      view.values = half_values.data();
      view.unscales = unscales.data();
      HalfFactorSolveF16c(view, y.data(), gathered.data());
      return;
    }
    for (int s = 0; s < ns; ++s) {  // L z = P b
      const int k0 = super[s], nc = super[s + 1] - k0, nr = pi[s + 1] - pi[s];
      const Block l(values.data() + px[s], nr, nc, Eigen::OuterStride<>(nr));
      auto ys = y.segment(k0, nc);
      l.topRows(nc).triangularView<Eigen::Lower>().solveInPlace(ys);
      if (nr == nc) continue;
      auto g = gathered.head(nr - nc);
      g.noalias() = l.bottomRows(nr - nc) * ys;
      const int* below = rows.data() + pi[s] + nc;
      for (int i = 0; i < nr - nc; ++i) y[below[i]] -= g[i];
    }
    for (int s = ns - 1; s >= 0; --s) {  // L^T w = z
      const int k0 = super[s], nc = super[s + 1] - k0, nr = pi[s + 1] - pi[s];
      const Block l(values.data() + px[s], nr, nc, Eigen::OuterStride<>(nr));
      auto ys = y.segment(k0, nc);
      if (nr > nc) {
        auto g = gathered.head(nr - nc);
        const int* below = rows.data() + pi[s] + nc;
        for (int i = 0; i < nr - nc; ++i) g[i] = y[below[i]];
        ys.noalias() -= l.bottomRows(nr - nc).transpose() * g;
      }
      l.topRows(nc).triangularView<Eigen::Lower>().transpose().solveInPlace(ys);
    }
  }
};

}  // namespace

struct CholmodSolver::Impl {
  Eigen::SparseMatrix<double> matrix;  // same structure as the pattern; values copied in
  Decomposition cholesky;
  SingleFactor single;
  bool analysed = false;
  bool factorized = false;
  bool has_single = false;
  // The solves may come from several threads (a factor shared between the FEM body and the scene's
  // compliance worker): CHOLMOD's solve writes its cholmod_common, the low-precision solve its
  // work vectors. Two locks, so the two kinds never wait for each other.
  mutable std::mutex cholmod_mutex, single_mutex;
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>()) {}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::Factorize(const SparsePattern& pattern, const Eigen::VectorXd& values, bool keep_single_precision,
                              bool half_storage) {
  Impl& s = *impl_;
  if (!s.analysed || s.matrix.rows() != pattern.structure.rows() ||
      s.matrix.nonZeros() != pattern.structure.nonZeros()) {
    s.matrix = pattern.structure;
    // Try AMD and METIS, keep the ordering with the sparser factor: on the 2,900-node box METIS
    // fills 12% fewer entries (every solve reads them all) and needs 25% fewer flops to factorise.
    cholmod_common& common = s.cholesky.cholmod();
    common.nmethods = 2;
    common.method[0].ordering = CHOLMOD_AMD;
    common.method[1].ordering = CHOLMOD_METIS;
    s.cholesky.analyzePattern(s.matrix);
    s.analysed = true;
  }
  std::copy(values.data(), values.data() + values.size(), s.matrix.valuePtr());
  {
    const SerialCholmodRegions serial;
    s.cholesky.factorize(s.matrix);
  }
  // Eigen 3.4 reports Success whatever CHOLMOD found.
  const cholmod_factor* l = FactorAccess::Of(s.cholesky);
  s.factorized = s.cholesky.info() == Eigen::Success && l && l->itype == CHOLMOD_INT && PositiveDefinite(*l);
  s.has_single = s.factorized && keep_single_precision && s.single.CopyFrom(*l, half_storage);
  return s.factorized;
}

bool CholmodSolver::factorized() const { return impl_->factorized; }

bool CholmodSolver::half_storage() const { return impl_->has_single && impl_->single.half; }

std::size_t CholmodSolver::low_precision_bytes() const {
  const SingleFactor& f = impl_->single;
  if (!impl_->has_single) return 0;
  return f.half ? f.half_values.size() * sizeof(std::uint16_t) : f.values.size() * sizeof(float);
}

void CholmodSolver::Solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const std::lock_guard lock(impl_->cholmod_mutex);
  x = impl_->cholesky.solve(b);
}

void CholmodSolver::Solve(const Eigen::Matrix<double, Eigen::Dynamic, 3>& b,
                          Eigen::Matrix<double, Eigen::Dynamic, 3>& x) const {
  const std::lock_guard lock(impl_->cholmod_mutex);
  x = impl_->cholesky.solve(b);
}

void CholmodSolver::SolveSinglePrecision(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (impl_->has_single) {
    const std::lock_guard lock(impl_->single_mutex);
    impl_->single.Solve(b, x);
  } else {
    Solve(b, x);
  }
}

void CholmodSolver::SolveSinglePrecisionTurned(const std::vector<Eigen::Matrix3d>& node_rotations,
                                               const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (3 * static_cast<Eigen::Index>(node_rotations.size()) != b.size())
    throw std::invalid_argument("CholmodSolver::SolveSinglePrecisionTurned: one rotation a node (3 rows) needed");
  if (impl_->has_single) {
    const std::lock_guard lock(impl_->single_mutex);
    impl_->single.SolveTurned(node_rotations, b, x);
    return;
  }
  Eigen::VectorXd turned(b.size()), solved;
  for (size_t i = 0; i < node_rotations.size(); ++i)
    turned.segment<3>(3 * i) = node_rotations[i].transpose() * b.segment<3>(3 * i);
  Solve(turned, solved);
  x.resize(b.size());
  for (size_t i = 0; i < node_rotations.size(); ++i) x.segment<3>(3 * i) = node_rotations[i] * solved.segment<3>(3 * i);
}

}  // namespace vesica::physics
