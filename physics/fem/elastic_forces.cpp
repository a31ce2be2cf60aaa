#include "physics/fem/elastic_forces.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "physics/fem/block_rows_simd.h"
#include "physics/fem/element_pass_simd.h"
#include "physics/fem/element_rotation.h"

namespace vesica::physics {

void SymmetricPatternMultiply(const SparsePattern& p, const Eigen::VectorXd& values, const Eigen::VectorXd& x,
                              Eigen::VectorXd& y) {
  // Column j of a symmetric matrix is its row j: a gather per output entry. The pattern is made of
  // 3x3 node blocks (BuildSparsePattern): the three columns of node b list the same rows, three
  // consecutive ones per neighbour, so one row index serves nine values (the memory-bound loop reads
  // a third fewer bytes than a scalar CSC product).
  const int nodes = static_cast<int>(p.structure.cols()) / 3;
  const int* outer = p.structure.outerIndexPtr();
  const int* inner = p.structure.innerIndexPtr();
  const double* v = values.data();
  const double* xs = x.data();
  y.resize(3 * nodes);
  if (BlockRowKernelsUseAvx2()) {
    BlockRowsView view;
    view.nodes = nodes;
    view.outer = outer;
    view.inner = inner;
    view.column_stride = p.column_stride.data();
    view.diagonal_slot = p.diagonal_slot.data();
    view.values = v;
    SymmetricPatternMultiplyAvx2(view, xs, y.data());
    return;
  }
  for (int b = 0; b < nodes; ++b) {
    const int begin = outer[3 * b], stride = p.column_stride[b];
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (int k = begin; k < begin + stride; k += 3) {
      const double* xa = xs + inner[k];  // rows 3a, 3a+1, 3a+2
      const double* c0 = v + k;
      s0 += c0[0] * xa[0] + c0[1] * xa[1] + c0[2] * xa[2];
      const double* c1 = c0 + stride;
      s1 += c1[0] * xa[0] + c1[1] * xa[1] + c1[2] * xa[2];
      const double* c2 = c1 + stride;
      s2 += c2[0] * xa[0] + c2[1] * xa[1] + c2[2] * xa[2];
    }
    y[3 * b] = s0;
    y[3 * b + 1] = s1;
    y[3 * b + 2] = s2;
  }
}

namespace {

double LinearForces(const FemModel& m, const Eigen::VectorXd& u, Eigen::VectorXd* tangent, Eigen::VectorXd* force) {
  if (tangent) *tangent = m.linear_stiffness_values;
  SymmetricPatternMultiply(m.pattern, m.linear_stiffness_values, u, *force);
  return 0.5 * u.dot(*force);
}

// Below this det F the warm-started iteration is not trusted (inversion): the SVD decides.
constexpr double kMinDetForIteration = 0.2;

// The scalar pass's rotation rule (the SIMD kernels redo their rare Mueller / SVD lanes with it).
Eigen::Matrix3d ElementRotation(const Eigen::Matrix3d& f, Eigen::Vector4d* q) {
  if (q && f.determinant() > kMinDetForIteration) return RotationByQuaternionIteration(f, *q, 30);  // stops early
  const Eigen::Matrix3d r = RotationFromDeformationGradient(f);
  if (q) *q = Eigen::Quaterniond(r).coeffs();
  return r;
}

// Per tet: f_a = R (V sigma) g_a with H = R^T F - I, eps = sym(H), sigma = lambda tr(eps) I +
// 2 mu eps, which equals sum_b K_ab (R^T x_b - X_b) of the 12x12 Hooke stiffness (sum_b d_b g_b^T
// = H), at a fraction of the cost; energy V (mu eps:eps + lambda tr(eps)^2 / 2). The tangent
// blocks R K_ab R^T = V (lambda r_a r_b^T + mu r_b r_a^T + mu (g_a . g_b) I) with r_a = R g_a.
double CorotationalForces(const FemModel& m, const Eigen::VectorXd& u, Eigen::VectorXd* tangent, Eigen::VectorXd* force,
                          std::vector<Eigen::Vector4d>* cache, double* smallest_turn_cosine) {
  double smallest_cosine = cache ? 1.0 : 0.0;  // |q_before . q_after|; without a cache: unknown
  if (cache && static_cast<int>(cache->size()) != m.rest_mesh.num_tets())
    cache->assign(m.rest_mesh.num_tets(), Eigen::Vector4d(0, 0, 0, 1));
  const auto& mesh = m.rest_mesh;
  const double lambda = m.lame_lambda_Pa, mu = m.lame_mu_Pa;
  force->setZero(u.size());
  if (tangent) tangent->setZero(m.pattern.structure.nonZeros());
  double* f_out = force->data();
  double* k_out = tangent ? tangent->data() : nullptr;
  double energy = 0.0;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const TetElement& e = m.elements[t];
    int node[4];
    Eigen::Vector3d x[4];
    for (int a = 0; a < 4; ++a) {
      node[a] = mesh.tets(t, a);
      x[a] = mesh.vertices.row(node[a]).transpose() + u.segment<3>(3 * node[a]);
    }
    Eigen::Matrix3d ds;
    ds << x[1] - x[0], x[2] - x[0], x[3] - x[0];
    const Eigen::Matrix3d f = ds * e.rest_shape_inverse;
    const Eigen::Vector4d q_before = cache ? (*cache)[t] : Eigen::Vector4d(0, 0, 0, 1);
    const Eigen::Matrix3d r = ElementRotation(f, cache ? &(*cache)[t] : nullptr);
    if (cache) smallest_cosine = std::min(smallest_cosine, std::abs(q_before.dot((*cache)[t])));
    Eigen::Matrix3d eps = r.transpose() * f;
    eps = 0.5 * (eps + eps.transpose()).eval();
    eps.diagonal().array() -= 1.0;
    const double trace = eps.trace();
    energy += e.rest_volume_m3 * (mu * eps.squaredNorm() + 0.5 * lambda * trace * trace);
    Eigen::Matrix3d stress = (2.0 * mu * e.rest_volume_m3) * eps;  // V sigma
    stress.diagonal().array() += lambda * e.rest_volume_m3 * trace;
    const Eigen::Matrix3d r_stress = r * stress;
    Eigen::Vector3d f_sum = Eigen::Vector3d::Zero();
    for (int a = 1; a < 4; ++a) {
      const Eigen::Vector3d fa = r_stress * e.shape_gradients[a];
      f_sum += fa;
      for (int i = 0; i < 3; ++i) f_out[3 * node[a] + i] += fa[i];
    }
    for (int i = 0; i < 3; ++i) f_out[3 * node[0] + i] -= f_sum[i];  // sum_a g_a = 0
    if (!k_out) continue;
    Eigen::Vector3d g[4];  // rotated gradients r_a = R g_a
    for (int a = 0; a < 4; ++a) g[a] = r * e.shape_gradients[a];
    const double lv = lambda * e.rest_volume_m3, mv = mu * e.rest_volume_m3;
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        Eigen::Matrix3d kr = lv * g[a] * g[b].transpose() + mv * g[b] * g[a].transpose();
        kr.diagonal().array() += mv * e.shape_gradients[a].dot(e.shape_gradients[b]);
        double* out_ab = k_out + m.pattern.block_slot[t][4 * a + b];
        const int stride_b = m.pattern.column_stride[node[b]];
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row) out_ab[c * stride_b + row] += kr(row, c);
        if (b == a) continue;
        double* out_ba = k_out + m.pattern.block_slot[t][4 * b + a];
        const int stride_a = m.pattern.column_stride[node[a]];
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row) out_ba[c * stride_a + row] += kr(c, row);
      }
  }
  if (smallest_turn_cosine) *smallest_turn_cosine = smallest_cosine;
  return energy;
}

ElementKernel SupportedKernel() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("fma"))
    return ElementKernel::kAvx512;
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return ElementKernel::kAvx2;
  return ElementKernel::kScalar;
}

ElementKernel EnvironmentKernel() {
  const char* name = std::getenv("VESICA_FEM_ELEMENT_KERNEL");
  if (!name) return ElementKernel::kAuto;
  if (!std::strcmp(name, "scalar")) return ElementKernel::kScalar;
  if (!std::strcmp(name, "avx2")) return ElementKernel::kAvx2;
  if (!std::strcmp(name, "avx512")) return ElementKernel::kAvx512;
  return ElementKernel::kAuto;
}

// The SIMD kernels' view of the model's element batches, for the vector x and output y.
ElementPassArgs BatchArgs(const FemModel& m, const Eigen::VectorXd& x, double* rotation_cache, double* y) {
  ElementPassArgs args;
  args.rest = m.element_batches.rest.data();
  args.dofs = m.element_batches.dofs.data();
  args.num_tets = m.element_batches.num_tets;
  args.lambda_Pa = m.lame_lambda_Pa;
  args.mu_Pa = m.lame_mu_Pa;
  args.displacement = x.data();
  args.rotation_cache = rotation_cache;
  args.force = y;
  return args;
}

size_t TurnedGradientSize(const FemModel& m) {
  return m.element_batches.rest.size() / kElementBatchFields * kTurnedGradientFields;
}

// The vectorised corotational pass applies (with a rotation cache): the SIMD kernel runs, the
// batches cover the mesh and, for a tangent, the node pairs exist.
bool SimdPassApplies(const FemModel& m, ElementKernel kernel, bool wants_tangent) {
  return m.settings.element_model == ElementModel::kCorotational && kernel != ElementKernel::kScalar &&
         m.element_batches.num_tets == m.rest_mesh.num_tets() && (!wants_tangent || m.tangent_blocks.num_pairs() > 0);
}

double SimdCorotationalForces(const FemModel& m, ElementKernel kernel, const Eigen::VectorXd& u,
                              Eigen::VectorXd* tangent, const FloatTangentRows* float_tangent, double tangent_scale,
                              Eigen::VectorXd* force, std::vector<Eigen::Vector4d>& cache,
                              HugePageVector<double>* turned_gradients, double* smallest_turn_cosine,
                              const PassProducts* products) {
  if (static_cast<int>(cache.size()) != m.rest_mesh.num_tets())
    cache.assign(m.rest_mesh.num_tets(), Eigen::Vector4d(0, 0, 0, 1));
  force->setZero(u.size());
  ElementPassArgs args = BatchArgs(m, u, cache.data()->data(), force->data());  // Vector4d: 4 packed doubles
  if (tangent) {
    tangent->resize(m.pattern.structure.nonZeros());  // the pass writes every value
    args.tangent = tangent->data();
  } else if (float_tangent) {
    args.tangent_rows = float_tangent->values;
    args.tangent_row_offsets = float_tangent->pair_offsets->data();
  }
  if (tangent || float_tangent) {
    args.tangent_scale = tangent_scale;
    args.tangent_blocks = &m.tangent_blocks;
    thread_local std::vector<double> corner_vectors;
    corner_vectors.resize(static_cast<size_t>(kCornerVectorFields) * m.rest_mesh.num_tets());
    args.corner_vectors = corner_vectors.data();
  }
  if (turned_gradients) {
    turned_gradients->resize(TurnedGradientSize(m));
    args.turned_gradients_out = turned_gradients->data();
  }
  args.smallest_turn_cosine = smallest_turn_cosine;
  if (products) {
    args.num_products = products->count;
    for (int k = 0; k < products->count; ++k) {
      products->y[k]->setZero(u.size());
      args.product_in[k] = products->x[k]->data();
      args.product_out[k] = products->y[k]->data();
    }
  }
  return kernel == ElementKernel::kAvx512 ? ElementPassAvx512(args) : ElementPassAvx2(args);
}

}  // namespace

void ScalarElementRotation(const double* f, double* q, double* r) {
  Eigen::Map<Eigen::Vector4d> q_map(q);
  Eigen::Vector4d q_in = q_map;
  using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  Eigen::Map<RowMajor3> r_map(r);
  r_map = ElementRotation(Eigen::Map<const RowMajor3>(f), &q_in);
  q_map = q_in;
}

void CorotationalTangentTimes(const FemModel& m, const std::vector<Eigen::Vector4d>& cache, const Eigen::VectorXd& x,
                              Eigen::VectorXd& y, const HugePageVector<double>* turned_gradients) {
  y.setZero(x.size());
  const ElementKernel kernel = ResolveElementKernel(m.settings.element_kernel);
  if (kernel != ElementKernel::kScalar && m.element_batches.num_tets == m.rest_mesh.num_tets()) {
    ElementPassArgs args =
        BatchArgs(m, x, const_cast<double*>(cache.data()->data()), y.data());  // the cache is read only here
    if (turned_gradients && turned_gradients->size() == TurnedGradientSize(m))
      args.turned_gradients = turned_gradients->data();
    (kernel == ElementKernel::kAvx512 ? TangentProductAvx512 : TangentProductAvx2)(args);
    return;
  }
  const auto& mesh = m.rest_mesh;
  const double lambda = m.lame_lambda_Pa, mu = m.lame_mu_Pa;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const TetElement& e = m.elements[t];
    Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();  // sum_b x_b g_b^T
    for (int b = 0; b < 4; ++b) grad += x.segment<3>(3 * mesh.tets(t, b)) * e.shape_gradients[b].transpose();
    const Eigen::Matrix3d r = Eigen::Quaterniond(cache[t]).toRotationMatrix();
    Eigen::Matrix3d eps = r.transpose() * grad;
    eps = 0.5 * (eps + eps.transpose()).eval();
    Eigen::Matrix3d stress = (2.0 * mu * e.rest_volume_m3) * eps;
    stress.diagonal().array() += lambda * e.rest_volume_m3 * eps.trace();
    const Eigen::Matrix3d r_stress = r * stress;
    for (int b = 0; b < 4; ++b) y.segment<3>(3 * mesh.tets(t, b)) += r_stress * e.shape_gradients[b];
  }
}

ElementKernel ResolveElementKernel(ElementKernel requested) {
  static const ElementKernel supported = SupportedKernel();
  static const ElementKernel from_environment = EnvironmentKernel();
  if (requested == ElementKernel::kAuto)
    requested = from_environment == ElementKernel::kAuto ? supported : from_environment;
  // The enumerators are ordered narrow to wide.
  return static_cast<int>(requested) <= static_cast<int>(supported) ? requested : supported;
}

namespace {
double LargestTurn(double smallest_turn_cosine) {
  return smallest_turn_cosine > 0.0 ? 2.0 * std::acos(std::min(1.0, smallest_turn_cosine))
                                    : std::numeric_limits<double>::infinity();
}
}  // namespace

std::vector<int> FloatTangentRowOffsets(const TangentBlocks& blocks, const std::vector<int>& value_index_of_slots) {
  const size_t pairs = blocks.slot_ab.size();
  std::vector<int> offsets(2 * pairs);
  for (size_t p = 0; p < pairs; ++p) {
    offsets[2 * p] = value_index_of_slots[blocks.slot_ab[p]];  // entry (3a, 3b): row 0 of block (b, a)
    offsets[2 * p + 1] = value_index_of_slots[blocks.slot_ba[p]];
  }
  return offsets;
}

bool FloatTangentAvailable(const FemModel& model) {
  return SimdPassApplies(model, ResolveElementKernel(model.settings.element_kernel), true);
}

double ComputeElasticForcesFloatTangent(const FemModel& model, const Eigen::VectorXd& u,
                                        const FloatTangentRows& tangent, double tangent_scale,
                                        Eigen::VectorXd* internal_force_N, std::vector<Eigen::Vector4d>* rotation_cache,
                                        HugePageVector<double>* turned_gradients, double* largest_turn_rad,
                                        const PassProducts* products) {
  double smallest_turn_cosine = 1.0;
  const double energy = SimdCorotationalForces(model, ResolveElementKernel(model.settings.element_kernel), u, nullptr,
                                               &tangent, tangent_scale, internal_force_N, *rotation_cache,
                                               turned_gradients, &smallest_turn_cosine, products);
  if (largest_turn_rad) *largest_turn_rad = LargestTurn(smallest_turn_cosine);
  return energy;
}

double ComputeElasticForces(const FemModel& model, const Eigen::VectorXd& u, Eigen::VectorXd* tangent_values,
                            Eigen::VectorXd* internal_force_N, std::vector<Eigen::Vector4d>* rotation_cache,
                            HugePageVector<double>* turned_gradients, double* largest_turn_rad, double tangent_scale,
                            const PassProducts* products) {
  const ElementKernel kernel = ResolveElementKernel(model.settings.element_kernel);
  double smallest_turn_cosine = 1.0;  // |q_before . q_after| = cos(turn / 2)
  double energy = 0.0;
  if (products && products->count > 0 &&
      (!rotation_cache || model.settings.element_model != ElementModel::kCorotational))
    throw std::invalid_argument("ComputeElasticForces: products need a corotational body and a rotation cache");
  if (rotation_cache && SimdPassApplies(model, kernel, tangent_values != nullptr)) {
    // writes every turned gradient: no clear
    energy = SimdCorotationalForces(model, kernel, u, tangent_values, nullptr, tangent_scale, internal_force_N,
                                    *rotation_cache, turned_gradients, &smallest_turn_cosine, products);
  } else {
    if (turned_gradients) turned_gradients->clear();  // only the SIMD pass fills them
    if (model.settings.element_model == ElementModel::kLinear)
      energy = LinearForces(model, u, tangent_values, internal_force_N);
    else
      energy = CorotationalForces(model, u, tangent_values, internal_force_N, rotation_cache, &smallest_turn_cosine);
    if (tangent_values && tangent_scale != 1.0) *tangent_values *= tangent_scale;
    for (int k = 0; products && k < products->count; ++k)
      CorotationalTangentTimes(model, *rotation_cache, *products->x[k], *products->y[k]);
  }
  if (largest_turn_rad) *largest_turn_rad = LargestTurn(smallest_turn_cosine);
  return energy;
}

}  // namespace vesica::physics
