#include "physics/fem/fem_body.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <sstream>

#include "physics/fem/attachment_springs.h"
#include "physics/fem/cholmod_solver.h"
#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_error.h"
#include "physics/fem/increment_extrapolation.h"
#include "physics/fem/local_block_correction.h"
#include "physics/fem/pcg_solver.h"
#include "physics/fem/rotated_factor_preconditioner.h"
#include "physics/fem/time_integrator.h"

namespace vesica::physics {

struct FemBody::Workspace {
  // S (SystemValuesFromTangent) at the state it was assembled at, Dirichlet rows and columns the
  // identity's; no copy of K_t is kept (TangentTimes recovers K_t x from S). Not written when
  // TangentInFloatRows (S is then float_rows alone).
  Eigen::VectorXd system_values;
  Eigen::VectorXd internal_force;
  double elastic_energy = 0.0;
  bool system_assembled = false;  // S exists (for the last step, or the current state)
  bool acceleration_valid = false;
  // The cumulative energy guard: the energy at the body's first step, and the work done on it since
  // (the external forces' in accepted steps, and the energy SetState's jumps added); a step may not
  // take the energy past max_energy_growth times their sum (a per-step bound alone lets it grow
  // geometrically).
  double energy_reference_J = 0.0;
  double energy_added_J = 0.0;
  double last_energy_after_J = 0.0;  // the last accepted step's energy
  bool energy_reference_set = false;
  bool state_was_set = false;        // SetState since the last accepted step
  bool linear_system_built = false;  // a linear body's S is built once (and after attachment changes)
  AttachmentSprings attachment;
  Eigen::VectorXd last_increment;        // PCG warm start
  IncrementExtrapolation extrapolation;  // kRotatedFactorPcg: warm start from the last increments
  Eigen::VectorXd warm_start_product;    // S times the kRotatedFactorPcg warm start
  // Step's products with K_t taken in the element pass (ProductsMatrixFree): the warm start
  // predicted before the pass (used by the next SolveSystem when warm_start_from_pass), its
  // free part's K_t product, and the Newmark damping drive's.
  Eigen::VectorXd pass_warm_start, pass_warm_start_free, pass_warm_start_product, damping_drive_product;
  bool warm_start_from_pass = false;
  Eigen::VectorXd solution_product;  // S du after a kRotatedFactorPcg solve (b - r)
  bool solution_product_valid = false;
  std::vector<Eigen::Vector4d> rotations;   // corotational warm start, per tet
  HugePageVector<double> turned_gradients;  // R grad N per tet from the last matrix-free pass
  BlockJacobiPreconditioner jacobi;
  FloatBlockRows float_rows;  // settings.rotated_factor_float_sweeps: the sweeps' copy of S
  bool float_sweeps = false;
  // TangentInFloatRows: where the element pass writes each node pair's blocks in float_rows
  // (FloatTangentRowOffsets), and where each dof's diagonal entry and each of the model's
  // constrained slots live there. Built on first use.
  std::vector<int> float_pair_offsets, float_diagonal_index, float_constrained_index;
  CholmodSolver cholmod;
  bool factor_matches_system = false;
  bool force_refactor = false;  // attachment changed: refactorise even between refreshes
  int steps_since_factor = 0;
  // kRotatedFactorPcg: factor of the rest system and the nodes' rotations (quaternions x y z w
  // and matrices) that turn it into the current frame.
  std::shared_ptr<const CholmodSolver> rest_factor;  // null until the first solve factorises
  // Attachments changed: the rest factor being computed on a worker, adopted when
  // steps_until_adopt reaches 0 (settings.rotated_factor_adopt_steps).
  RestFactorFuture pending_rest_factor;
  int steps_until_adopt = 0;
  // Sum of the element passes' largest tet turns since the node rotations were last computed
  // (settings.rotated_factor_rotation_refresh_rad); infinite until the first time.
  double rotation_drift_rad = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector4d> node_quaternions;
  std::vector<Eigen::Matrix3d> node_rotations;
  std::vector<char> node_has_fixed_axis;
  // Tets around each node (CSR: node n's are node_tets[node_tet_begin[n] .. node_tet_begin[n+1])),
  // with their rest volumes: the node rotations gather instead of scattering from every tet.
  std::vector<int> node_tet_begin, node_tets;
  std::vector<double> node_tet_volumes;
  // Per node, 1 - |sum of its tets' aligned quaternions, volume-weighted| / their volume: 0 where
  // its tets turn alike, larger where they turn apart (and the turned factor fits worst).
  std::vector<double> node_rotation_spread;
  LocalBlockCorrection local_correction;  // settings.rotated_factor_local_share
  RotatedFactorPreconditioner preconditioner;
};

FemBody::FemBody(std::shared_ptr<const FemModel> model)
    : model_(std::move(model)), work_(std::make_unique<Workspace>()) {
  if (!model_) throw FemError("FemBody: null model");
  const int n = model_->num_dofs();
  state_.displacement_m.setZero(n);
  state_.velocity_m_per_s.setZero(n);
  state_.acceleration_m_per_s2.setZero(n);
  state_.external_force_N.setZero(n);
  work_->last_increment.setZero(n);
}
FemBody::~FemBody() = default;
FemBody::FemBody(FemBody&&) noexcept = default;
FemBody& FemBody::operator=(FemBody&&) noexcept = default;

namespace {
// A constrained point's weights in its tet: beyond this it lies tens of tets away.
constexpr double kMaxBarycentricWeight = 100.0;

void CheckVector(const FemModel& m, const Eigen::VectorXd& x, const char* what) {
  const std::string& name = m.settings.body_name;
  if (x.size() != m.num_dofs()) {
    std::ostringstream os;
    os << name << ": " << what << " has " << x.size() << " entries, expected 3 x " << m.num_nodes();
    throw FemError(os.str());
  }
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i])) {
      std::ostringstream os;
      os << name << ": " << what << " of node " << i / 3 << " (axis " << i % 3 << ") is not finite";
      throw FemError(os.str());
    }
}
}  // namespace

void FemBody::SetExternalForces(const Eigen::VectorXd& f) {
  CheckVector(*model_, f, "external force");
  state_.external_force_N = f;
}

RestFactorFuture FemBody::PendingRestFactor() const { return work_->pending_rest_factor; }

void FemBody::SetState(const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  CheckVector(*model_, u, "displacement");
  CheckVector(*model_, v, "velocity");
  state_.displacement_m = u;
  state_.velocity_m_per_s = v;
  work_->acceleration_valid = false;
  work_->system_assembled = false;
  work_->state_was_set = true;
}

void FemBody::SetAttachmentStiffness(const Eigen::VectorXd& stiffness, const Eigen::VectorXd& damping) {
  Workspace& w = *work_;
  AttachmentSprings next = MakeAttachmentSprings(model_->settings.body_name, model_->num_nodes(), stiffness, damping);
  if (!next.any && !w.attachment.any) return;  // zero before and after: nothing to rebuild
  w.attachment = std::move(next);
  // S changes: rebuild it at the next step (a linear body refactorises once, then keeps it).
  w.system_assembled = false;
  w.linear_system_built = false;
  w.factor_matches_system = false;
  const FemSettings& s = model_->settings;
  if (s.solver == LinearSolverKind::kRotatedFactorPcg && s.rotated_factor_adopt_steps > 0 && w.rest_factor &&
      w.rest_factor->factorized()) {
    if (w.pending_rest_factor.valid()) w.pending_rest_factor.wait();  // superseded
    Eigen::VectorXd rest_system;
    SystemValuesFromTangent(model_->linear_stiffness_values, rest_system);
    w.pending_rest_factor =
        std::async(std::launch::async,
                   [model = model_, values = std::move(rest_system)]() -> std::shared_ptr<const CholmodSolver> {
                     auto factor = std::make_shared<CholmodSolver>();
                     if (!factor->Factorize(model->pattern, values, model->settings.rotated_factor_single_precision,
                                            model->settings.rotated_factor_half_precision))
                       return nullptr;
                     return factor;
                   })
            .share();
    w.steps_until_adopt = s.rotated_factor_adopt_steps;
    return;
  }
  w.force_refactor = true;
}

void FemBody::DampingTimes(const Eigen::VectorXd& x, Eigen::VectorXd& y, const Eigen::VectorXd* tangent_x) const {
  const FemSettings& s = model_->settings;
  y.setZero(x.size());
  if (x.isZero(0.0)) return;  // backward Euler's damping drive: skip the product
  if (s.rayleigh_mass_per_s != 0.0) y += s.rayleigh_mass_per_s * model_->MassTimes(x);
  if (s.rayleigh_stiffness_s != 0.0) {
    Eigen::VectorXd kx;
    if (!tangent_x) TangentTimes(x, kx);
    y += s.rayleigh_stiffness_s * (tangent_x ? *tangent_x : kx);
  }
}

bool FemBody::MatrixFree() const { return TangentIsMatrixFree(model_->settings); }

bool FemBody::ProductsMatrixFree() const { return ProductsAreMatrixFree(model_->settings); }

void FemBody::TangentTimes(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  if (ProductsMatrixFree()) {
    CorotationalTangentTimes(*model_, work_->rotations, x, y, &work_->turned_gradients);
    return;
  }
  // From S = stiffness K_t + mass M + springs, the only matrix kept: on the free dofs
  // K_t x = (S x - mass M x - springs x) / stiffness, x's fixed entries taken as 0 (S's fixed rows
  // and columns are the identity's). Fixed rows get 0; every caller drops them.
  const FemModel& m = *model_;
  const Workspace& w = *work_;
  const SystemScales scale = SystemMatrixScales(m.settings);
  const Eigen::VectorXd free_x = x.cwiseProduct(m.free_dofs);
  SymmetricPatternMultiply(m.pattern, w.system_values, free_x, y);
  if (m.uses_consistent_mass())
    y -= scale.mass * (PatternMatrix(m.pattern, m.consistent_mass_values) * free_x);
  else
    y -= scale.mass * m.lumped_mass_kg.cwiseProduct(free_x);
  if (w.attachment.any) {
    const double c_damping = IntegratorCoefficients(m.settings).damping;
    y -= (w.attachment.stiffness_N_per_m + c_damping * w.attachment.damping_Ns_per_m).cwiseProduct(free_x);
  }
  y /= scale.stiffness;
  for (int i : m.fixed_dofs) y[i] = 0.0;
}

void FemBody::SystemTimes(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // PCG's directions and warm starts are 0 on the fixed dofs already: then x is its own free part,
  // and no masked copy is made.
  const FemModel& m = *model_;
  bool fixed_zero = true;
  for (int i : m.fixed_dofs) fixed_zero = fixed_zero && x[i] == 0.0;
  if (fixed_zero) {
    TangentTimes(x, y);
  } else {
    const Eigen::VectorXd masked = x.cwiseProduct(m.free_dofs);
    TangentTimes(masked, y);
  }
  SystemTimesFromTangentProduct(x, y);
}

void FemBody::SystemTimesFromTangentProduct(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // S = stiffness_scale K_t + mass_scale M + springs (k + c_D d), with the rows and columns of fixed
  // dofs replaced by the identity's (as SystemValuesFromTangent writes them).
  const FemModel& m = *model_;
  const FemSettings& s = m.settings;
  const Workspace& w = *work_;
  const SystemCoefficients c = IntegratorCoefficients(s);
  const auto [mass_scale, stiffness_scale] = SystemMatrixScales(s);
  bool fixed_zero = true;
  for (int i : m.fixed_dofs) fixed_zero = fixed_zero && x[i] == 0.0;
  Eigen::VectorXd masked;
  if (!fixed_zero) masked = x.cwiseProduct(m.free_dofs);
  const Eigen::VectorXd& free_x = fixed_zero ? x : masked;
  if (m.uses_consistent_mass())
    y = stiffness_scale * y + mass_scale * (PatternMatrix(m.pattern, m.consistent_mass_values) * free_x);
  else  // one pass over the vectors
    y = stiffness_scale * y + mass_scale * m.lumped_mass_kg.cwiseProduct(free_x);
  if (w.attachment.any)
    y += (w.attachment.stiffness_N_per_m + c.damping * w.attachment.damping_Ns_per_m).cwiseProduct(free_x);
  for (int i : m.fixed_dofs) y[i] = x[i];
}

double FemBody::TangentQuadraticForm(const Eigen::VectorXd& du) const {
  const FemModel& m = *model_;
  const Workspace& w = *work_;
  if (!w.solution_product_valid || m.uses_consistent_mass() || w.solution_product.size() != du.size()) {
    Eigen::VectorXd k_du;
    TangentTimes(du, k_du);
    return du.dot(k_du);
  }
  // du . S du = stiffness_scale du.K du + sum over free dofs of (mass_scale m + k + c_D d) du^2;
  // fixed dofs have du = 0 (their rows are the identity's and the right-hand side is 0 there).
  const FemSettings& s = m.settings;
  const SystemCoefficients c = IntegratorCoefficients(s);
  const auto [mass_scale, stiffness_scale] = SystemMatrixScales(s);
  double diagonal = mass_scale * du.cwiseAbs2().dot(m.lumped_mass_kg.cwiseProduct(m.free_dofs));
  if (w.attachment.any)
    diagonal += du.cwiseAbs2().dot(
        (w.attachment.stiffness_N_per_m + c.damping * w.attachment.damping_Ns_per_m).cwiseProduct(m.free_dofs));
  return (du.dot(w.solution_product) - diagonal) / stiffness_scale;
}

bool FemBody::TangentInFloatRows() const {
  const FemModel& m = *model_;
  const FemSettings& s = m.settings;
  return ProductsMatrixFree() && s.rotated_factor_gauss_seidel && s.rotated_factor_float_sweeps &&
         !m.uses_consistent_mass() && FloatBlockRows::available() && FloatTangentAvailable(m);
}

void FemBody::AssembleSystem(const Eigen::VectorXd& u, const PassProducts* products) {
  const FemModel& m = *model_;
  const FemSettings& s = m.settings;
  Workspace& w = *work_;
  const bool linear = s.element_model == ElementModel::kLinear;
  if (MatrixFree()) {  // forces and rotations only: the solver applies K_t element by element
    double turn = 0.0;
    w.elastic_energy =
        ComputeElasticForces(m, u, nullptr, &w.internal_force, &w.rotations, &w.turned_gradients, &turn, 1.0, products);
    w.rotation_drift_rad += turn;
    w.system_assembled = true;
    return;
  }
  if (TangentInFloatRows()) {  // S only for the sweeps: the pass writes its stiffness as floats
    if (w.float_pair_offsets.empty()) {
      w.float_rows.Reshape(m.pattern);
      const std::vector<int> index = w.float_rows.ValueIndexOfSlots(m.pattern);
      w.float_pair_offsets = FloatTangentRowOffsets(m.tangent_blocks, index);
      w.float_diagonal_index.resize(m.num_dofs());
      for (int i = 0; i < m.num_dofs(); ++i) w.float_diagonal_index[i] = index[m.pattern.diagonal_slot[i]];
      w.float_constrained_index.clear();
      for (int k : m.constrained_slots) w.float_constrained_index.push_back(index[k]);
    }
    double turn = 0.0;
    w.elastic_energy = ComputeElasticForcesFloatTangent(m, u, {w.float_rows.values(), &w.float_pair_offsets},
                                                        SystemMatrixScales(s).stiffness, &w.internal_force,
                                                        &w.rotations, &w.turned_gradients, &turn, products);
    w.rotation_drift_rad += turn;
    w.system_assembled = true;
    AddSystemTermsToFloatRows();
    w.factor_matches_system = false;
    return;
  }
  // A linear body's K never changes: S is built once, then only f = K u is needed. The pass writes
  // stiffness K_t straight into S's values; the mass and spring terms follow on the diagonal. With
  // matrix-free products (the sweeps' S assembled all the same) it also leaves the turned gradients.
  double turn = 0.0;
  w.elastic_energy = ComputeElasticForces(
      m, u, (linear && w.linear_system_built) ? nullptr : &w.system_values, &w.internal_force, &w.rotations,
      ProductsMatrixFree() ? &w.turned_gradients : nullptr, &turn, SystemMatrixScales(s).stiffness, products);
  w.rotation_drift_rad += turn;
  w.system_assembled = true;
  if (linear && w.linear_system_built) return;
  AddSystemTerms(w.system_values);
  w.linear_system_built = linear;
  w.factor_matches_system = false;
}

void FemBody::SystemValuesFromTangent(const Eigen::VectorXd& tangent, Eigen::VectorXd& system) const {
  system = SystemMatrixScales(model_->settings).stiffness * tangent;
  AddSystemTerms(system);
}

namespace {
// S's terms besides the stiffness: lumped mass (unless `consistent_mass_added`) and spring
// increments like K du and D v+ (k + c_D d) on the diagonal, then the Dirichlet rows and columns
// made the identity's. diagonal(i) is dof i's diagonal entry, constrained(j) the entry of the
// model's j-th constrained slot, in whatever storage S has.
template <class Diagonal, class Constrained>
void AddDiagonalTermsAndDirichlet(const FemModel& m, const AttachmentSprings& springs, bool consistent_mass_added,
                                  Diagonal diagonal, Constrained constrained) {
  const FemSettings& s = m.settings;
  const double mass_scale = SystemMatrixScales(s).mass;
  if (!consistent_mass_added)
    for (int i = 0; i < m.num_dofs(); ++i) diagonal(i) += mass_scale * m.lumped_mass_kg[i];
  if (springs.any) {
    const double c_damping = IntegratorCoefficients(s).damping;
    const Eigen::VectorXd& k = springs.stiffness_N_per_m;
    const Eigen::VectorXd& d = springs.damping_Ns_per_m;
    for (int i = 0; i < m.num_dofs(); ++i) diagonal(i) += k[i] + c_damping * d[i];
  }
  for (size_t j = 0; j < m.constrained_slots.size(); ++j) constrained(j) = 0;
  for (int i : m.fixed_dofs) diagonal(i) = 1;
}
}  // namespace

void FemBody::AddSystemTerms(Eigen::VectorXd& system) const {
  const FemModel& m = *model_;
  if (m.uses_consistent_mass()) system += SystemMatrixScales(m.settings).mass * m.consistent_mass_values;
  AddDiagonalTermsAndDirichlet(
      m, work_->attachment, m.uses_consistent_mass(),
      [&](int i) -> double& { return system[m.pattern.diagonal_slot[i]]; },
      [&](size_t j) -> double& { return system[m.constrained_slots[j]]; });
}

void FemBody::AddSystemTermsToFloatRows() {
  Workspace& w = *work_;
  float* values = w.float_rows.values();
  AddDiagonalTermsAndDirichlet(
      *model_, w.attachment, false, [&](int i) -> float& { return values[w.float_diagonal_index[i]]; },
      [&](size_t j) -> float& { return values[w.float_constrained_index[j]]; });
}

void FemBody::UpdateNodeRotations() {
  // Each node turns with the volume-weighted mean of its elements' quaternions (signs aligned with
  // the node's last quaternion, so q and -q do not cancel). Nodes with a fixed axis keep R = I:
  // the preconditioner must not mix a fixed dof with free ones.
  const FemModel& m = *model_;
  Workspace& w = *work_;
  const int nodes = m.num_nodes();
  const int tets = m.rest_mesh.num_tets();
  if (static_cast<int>(w.node_quaternions.size()) != nodes) {
    w.node_quaternions.assign(nodes, Eigen::Vector4d(0, 0, 0, 1));
    w.node_rotations.assign(nodes, Eigen::Matrix3d::Identity());
    w.node_has_fixed_axis.assign(nodes, 0);
    w.node_rotation_spread.assign(nodes, 0.0);
    for (int i : m.fixed_dofs) w.node_has_fixed_axis[i / 3] = 1;
    w.node_tet_begin.assign(nodes + 1, 0);
    for (int t = 0; t < tets; ++t)
      for (int a = 0; a < 4; ++a) ++w.node_tet_begin[m.rest_mesh.tets(t, a) + 1];
    for (int n = 0; n < nodes; ++n) w.node_tet_begin[n + 1] += w.node_tet_begin[n];
    w.node_tets.resize(4 * static_cast<size_t>(tets));
    w.node_tet_volumes.resize(4 * static_cast<size_t>(tets));
    std::vector<int> next(w.node_tet_begin.begin(), w.node_tet_begin.end() - 1);
    for (int t = 0; t < tets; ++t)
      for (int a = 0; a < 4; ++a) {
        const int k = next[m.rest_mesh.tets(t, a)]++;
        w.node_tets[k] = t;
        w.node_tet_volumes[k] = m.element_batches.rest_volume_m3(t);
      }
  }
  if (static_cast<int>(w.rotations.size()) != tets) return;  // linear body: R = I
  for (int n = 0; n < nodes; ++n) {
    if (w.node_has_fixed_axis[n]) continue;
    const Eigen::Vector4d last = w.node_quaternions[n];
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    double volume = 0.0;
    for (int k = w.node_tet_begin[n]; k < w.node_tet_begin[n + 1]; ++k) {
      const Eigen::Vector4d& q = w.rotations[w.node_tets[k]];
      sum += (q.dot(last) < 0.0 ? -w.node_tet_volumes[k] : w.node_tet_volumes[k]) * q;
      volume += w.node_tet_volumes[k];
    }
    const double norm = sum.norm();
    if (!(norm > 0.0)) continue;
    w.node_rotation_spread[n] = std::max(0.0, 1.0 - norm / volume);
    w.node_quaternions[n] = sum / norm;
    w.node_rotations[n] = Eigen::Quaterniond(w.node_quaternions[n]).toRotationMatrix();
  }
}

bool FemBody::SolveSystem(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, double tolerance, int max_iterations,
                          StepReport* report) {
  const FemModel& m = *model_;
  const FemSettings& s = m.settings;
  Workspace& w = *work_;
  PcgResult r;
  w.solution_product_valid = false;
  if (s.solver == LinearSolverKind::kCholmod) {
    const bool linear = s.element_model == ElementModel::kLinear;
    const bool refresh = !w.cholmod.factorized() || w.force_refactor ||
                         (!linear && !w.factor_matches_system && w.steps_since_factor + 1 >= s.cholmod_refresh_steps);
    if (refresh) {
      if (!w.cholmod.Factorize(m.pattern, w.system_values)) return false;
      if (report) report->factorised = true;
      w.force_refactor = false;
      w.factor_matches_system = true;
      w.steps_since_factor = 0;
    } else if (!linear && !w.factor_matches_system) {
      ++w.steps_since_factor;
    }
    if (linear || w.factor_matches_system) {
      w.cholmod.Solve(rhs, du);
      if (report) report->solver_iterations = 0, report->relative_residual = 0.0;
      return du.allFinite();
    }
    // Stale factor of a corotational body: it preconditions PCG on the current system.
    du = w.last_increment;
    r = SolvePcg(
        m.pattern, w.system_values, rhs, du,
        [&](const Eigen::VectorXd& res, Eigen::VectorXd& z) { w.cholmod.Solve(res, z); }, tolerance, max_iterations);
  } else if (s.solver == LinearSolverKind::kRotatedFactorPcg) {
    if (!w.rest_factor || !w.rest_factor->factorized() || w.force_refactor) {
      Eigen::VectorXd rest_system;
      SystemValuesFromTangent(m.linear_stiffness_values, rest_system);
      auto factor = std::make_shared<CholmodSolver>();
      if (!factor->Factorize(m.pattern, rest_system, s.rotated_factor_single_precision,
                             s.rotated_factor_half_precision))
        return false;
      if (report) report->factorised = true;
      w.rest_factor = std::move(factor);
      w.force_refactor = false;
    }
    if (w.rotation_drift_rad >= s.rotated_factor_rotation_refresh_rad) {
      UpdateNodeRotations();
      w.rotation_drift_rad = 0.0;
    }
    w.float_sweeps = s.rotated_factor_gauss_seidel && s.rotated_factor_float_sweeps && FloatBlockRows::available();
    const bool float_only = TangentInFloatRows();  // S exists as the float rows alone
    if (s.rotated_factor_gauss_seidel) {
      if (float_only)
        w.jacobi.Compute(w.float_rows);
      else
        w.jacobi.Compute(m.pattern, w.system_values);
    }
    if (w.float_sweeps && !float_only) w.float_rows.Update(m.pattern, w.system_values);
    const int local_nodes = std::min(s.rotated_factor_local_nodes_max,
                                     static_cast<int>(std::lround(s.rotated_factor_local_share * m.num_nodes())));
    if (local_nodes > 0 && !MatrixFree()) {
      // Not positive definite on those nodes: S is not either, and PCG reports it (Compute
      // leaves the correction empty).
      const std::vector<int> nodes = LargestSpreadNodes(w.node_rotation_spread, local_nodes);
      if (float_only)
        w.local_correction.Compute(
            m.num_dofs(),
            [&](int dof, std::vector<int>& columns, std::vector<double>& values) {
              w.float_rows.AppendRow(dof, columns, values);
            },
            nodes);
      else
        w.local_correction.Compute(m.pattern, w.system_values, nodes);
    } else {
      w.local_correction.Clear();
    }
    const MatrixOperator system_times = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
      if (ProductsMatrixFree())
        SystemTimes(x, y);
      else
        SymmetricPatternMultiply(m.pattern, w.system_values, x, y);
    };
    // Warm start: du extrapolated from the last increments (IncrementExtrapolation picks the
    // order), then scaled along itself to the minimum of the energy norm of the error,
    // alpha = du.b / du.S du: never worse than starting from zero in that norm. S du is the
    // product PCG starts from anyway, so the scale costs two dot products.
    // The step may have predicted it before its element pass, which then took its K_t product.
    const bool from_pass = w.warm_start_from_pass;
    w.warm_start_from_pass = false;
    if (from_pass)
      du.swap(w.pass_warm_start);
    else
      w.extrapolation.Predict(rhs.size(), du);
    const Eigen::VectorXd* warm_start_product = nullptr;
    if (from_pass || w.extrapolation.history() > 0) {
      if (from_pass) {
        w.warm_start_product.swap(w.pass_warm_start_product);
        SystemTimesFromTangentProduct(du, w.warm_start_product);
      } else {
        system_times(du, w.warm_start_product);
      }
      const double curvature = du.dot(w.warm_start_product);
      const double alpha = curvature > 0.0 ? du.dot(rhs) / curvature : 0.0;
      du *= alpha;
      w.warm_start_product *= alpha;
      warm_start_product = &w.warm_start_product;
    }
    RotatedFactorParts parts;
    parts.rest_factor = w.rest_factor.get();
    parts.single_precision = s.rotated_factor_single_precision;
    parts.node_rotations = &w.node_rotations;
    parts.sweeps = s.rotated_factor_gauss_seidel ? s.rotated_factor_sweeps : 0;
    parts.pattern = &m.pattern;
    parts.system_values = &w.system_values;
    parts.float_rows = w.float_sweeps ? &w.float_rows : nullptr;
    parts.inverse_diagonal = &w.jacobi.inverse_blocks();
    parts.local = &w.local_correction;
    r = SolvePcg(
        system_times, rhs, du,
        [&](const Eigen::VectorXd& res, Eigen::VectorXd& z) { w.preconditioner.Apply(parts, res, z); }, tolerance,
        max_iterations, warm_start_product, &w.solution_product);
    w.solution_product_valid = true;
  } else {
    w.jacobi.Compute(m.pattern, w.system_values);
    du = w.last_increment;
    r = SolvePcg(
        m.pattern, w.system_values, rhs, du,
        [&](const Eigen::VectorXd& res, Eigen::VectorXd& z) { w.jacobi.Apply(res, z); }, tolerance, max_iterations);
  }
  if (report) {
    report->solver_iterations = r.iterations;
    report->relative_residual = r.relative_residual;
    report->solver_spectrum = r.spectrum;
  }
  return !r.breakdown && du.allFinite();
}

StepReport FemBody::Step() {
  const FemModel& m = *model_;
  const FemSettings& s = m.settings;
  Workspace& w = *work_;
  StepReport report;
  const Eigen::VectorXd& u = state_.displacement_m;
  const Eigen::VectorXd& v = state_.velocity_m_per_s;
  const Eigen::VectorXd& f_ext = state_.external_force_N;

  // The warm start and the Newmark damping drive need products with K_t at this step's rotations:
  // with element-by-element products the element pass takes them (no passes of their own).
  PassProducts pass_products;
  Eigen::VectorXd mass_drive, damping_drive;
  const bool drives_before_pass = s.integrator == TimeIntegrator::kBackwardEuler || w.acceleration_valid;
  if (drives_before_pass) IntegratorDrives(s, v, state_.acceleration_m_per_s2, mass_drive, damping_drive);
  const bool damping_from_pass =
      ProductsMatrixFree() && drives_before_pass && s.rayleigh_stiffness_s != 0.0 && !damping_drive.isZero(0.0);
  if (damping_from_pass) pass_products.Add(damping_drive, w.damping_drive_product);
  w.warm_start_from_pass = ProductsMatrixFree() && w.extrapolation.history() > 0;
  if (w.warm_start_from_pass) {
    w.extrapolation.Predict(u.size(), w.pass_warm_start);
    // SystemTimes's product: K_t of the free part
    bool fixed_zero = true;
    for (int i : m.fixed_dofs) fixed_zero = fixed_zero && w.pass_warm_start[i] == 0.0;
    if (!fixed_zero) w.pass_warm_start_free = w.pass_warm_start.cwiseProduct(m.free_dofs);
    pass_products.Add(fixed_zero ? w.pass_warm_start : w.pass_warm_start_free, w.pass_warm_start_product);
  }
  AssembleSystem(u, pass_products.count > 0 ? &pass_products : nullptr);
  Eigen::VectorXd damping_v;
  // A rejected step must leave the state as it was, the acceleration included: keep what it was
  // if this step computes it (from equilibrium, Newmark's first step after SetState).
  const bool acceleration_computed = s.integrator == TimeIntegrator::kNewmark && !w.acceleration_valid;
  Eigen::VectorXd acceleration_before;
  if (acceleration_computed) {
    acceleration_before = state_.acceleration_m_per_s2;
    // Start from equilibrium M a = f_ext - f_int - D v, so Newmark's energy balance holds from step 1.
    DampingTimes(v, damping_v);
    const Eigen::VectorXd net = (f_ext - w.internal_force - damping_v).cwiseProduct(m.free_dofs);
    if (m.uses_consistent_mass()) {
      Eigen::VectorXd mass = m.consistent_mass_values;
      for (int k : m.constrained_slots) mass[k] = 0.0;
      for (int i : m.fixed_dofs) mass[m.pattern.diagonal_slot[i]] = 1.0;
      BlockJacobiPreconditioner pre;
      pre.Compute(m.pattern, mass);
      Eigen::VectorXd a = Eigen::VectorXd::Zero(net.size());
      SolvePcg(
          m.pattern, mass, net, a, [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { pre.Apply(r, z); }, 1e-14, 200);
      state_.acceleration_m_per_s2 = a;
    } else {
      state_.acceleration_m_per_s2 = net.cwiseQuotient(m.lumped_mass_kg);
    }
    w.acceleration_valid = true;
  }
  if (!drives_before_pass) IntegratorDrives(s, v, state_.acceleration_m_per_s2, mass_drive, damping_drive);
  Eigen::VectorXd rhs;
  if (m.uses_consistent_mass())
    rhs = f_ext - w.internal_force + m.MassTimes(mass_drive);
  else  // one pass, no temporary
    rhs = f_ext - w.internal_force + m.lumped_mass_kg.cwiseProduct(mass_drive);
  if (s.integrator != TimeIntegrator::kBackwardEuler) {  // backward Euler's damping drive is 0
    Eigen::VectorXd damping_term;
    DampingTimes(damping_drive, damping_term, damping_from_pass ? &w.damping_drive_product : nullptr);
    rhs += damping_term;
  }
  if (w.attachment.any) {
    // f_ext holds the springs' force at v; the step adds -d (v+ - v) = -d (c_D du - drive - v).
    rhs += w.attachment.damping_Ns_per_m.cwiseProduct(damping_drive + v);
  }
  for (int i : m.fixed_dofs) rhs[i] = 0.0;

  const double energy_before = KineticEnergy() + w.elastic_energy;
  report.energy_J = energy_before;
  if (!w.energy_reference_set) {
    w.energy_reference_J = energy_before;
    w.energy_reference_set = true;
  } else if (w.state_was_set) {  // SetState's jump counts as work done on the body
    w.energy_added_J += std::max(0.0, energy_before - w.last_energy_after_J);
    w.last_energy_after_J = energy_before;
  }
  w.state_was_set = false;
  auto reject = [&](const std::string& why) {
    if (acceleration_computed) {
      state_.acceleration_m_per_s2 = std::move(acceleration_before);
      w.acceleration_valid = false;
    }
    report.accepted = false;
    report.rejection_reason = s.body_name + ": step " + std::to_string(state_.steps) + " rolled back: " + why;
    w.last_increment.setZero();
    w.extrapolation.Clear();
    return report;
  };

  if (w.pending_rest_factor.valid() && --w.steps_until_adopt <= 0) {
    std::shared_ptr<const CholmodSolver> factor = w.pending_rest_factor.get();
    w.pending_rest_factor = {};
    if (factor)
      w.rest_factor = std::move(factor);
    else
      w.force_refactor = true;  // not positive definite: the solve refactorises, fails and rejects the step
  }
  Eigen::VectorXd du;
  const bool solved = SolveSystem(rhs, du, s.pcg_relative_tolerance, s.pcg_max_iterations, &report);
  w.warm_start_from_pass = false;  // consumed by this solve, or stale
  if (!solved) {
    if (!rhs.allFinite()) return reject("non-finite right-hand side");
    if (!std::isfinite(rhs.norm())) return reject("right-hand side too large (its norm overflows)");
    return reject("the linear solve failed (system not positive definite or non-finite)");
  }
  Eigen::VectorXd v_next, a_next;
  IntegratorUpdate(s, du, v, state_.acceleration_m_per_s2, v_next, a_next);
  if (!v_next.allFinite() || !a_next.allFinite()) return reject("non-finite velocity or acceleration");

  // Energy after the step, elastic part to second order about u (one product with K_t).
  const double elastic_after = w.elastic_energy + w.internal_force.dot(du) + 0.5 * TangentQuadraticForm(du);
  const double energy_after = 0.5 * m.MassQuadraticForm(v_next) + elastic_after;
  const double work = std::abs(f_ext.dot(du));
  if (!std::isfinite(energy_after) || energy_after > s.max_energy_growth * (energy_before + work) + s.energy_floor_J) {
    std::ostringstream os;
    os << "energy jumped from " << energy_before << " J to " << energy_after << " J (external work " << work << " J)";
    return reject(os.str());
  }
  const double energy_budget = w.energy_reference_J + w.energy_added_J + work;
  if (energy_after > s.max_energy_growth * energy_budget + s.energy_floor_J) {
    std::ostringstream os;
    os << "energy grew to " << energy_after << " J, over " << s.max_energy_growth << " x the energy at the start ("
       << w.energy_reference_J << " J) plus the work done on the body since (" << w.energy_added_J + work << " J)";
    return reject(os.str());
  }
  if (!(state_.displacement_m + du).allFinite()) return reject("non-finite displacement");
  if (!std::isfinite(state_.time_s + s.time_step_s)) return reject("the simulation time overflows");

  w.energy_added_J += work;
  w.last_energy_after_J = energy_after;
  state_.displacement_m += du;
  state_.velocity_m_per_s = std::move(v_next);
  state_.acceleration_m_per_s2 = std::move(a_next);
  state_.time_s += s.time_step_s;
  ++state_.steps;
  if (s.solver == LinearSolverKind::kRotatedFactorPcg)
    w.extrapolation.Push(du);  // its warm start; last_increment is the other solvers'
  else
    w.last_increment = du;
  report.accepted = true;
  report.energy_J = energy_after;
  return report;
}

Vertices FemBody::CurrentPositions() const {
  Vertices x = model_->rest_mesh.vertices;
  AsStackedVector(x) += state_.displacement_m;
  return x;
}

double FemBody::KineticEnergy() const {
  const Eigen::VectorXd& v = state_.velocity_m_per_s;
  return 0.5 * model_->MassQuadraticForm(v);
}

double FemBody::ElasticEnergy() const {
  // Rotations warm-started from the last step's (a copy: this is const) and the steps' kernel:
  // without a cache every tet takes the SVD, which costs as much as a whole step.
  std::vector<Eigen::Vector4d> rotations = work_->rotations;
  Eigen::VectorXd f;
  return ComputeElasticForces(*model_, state_.displacement_m, nullptr, &f, &rotations);
}

PointCompliance FemBody::Compliance(const std::vector<TetLocation>& points) {
  const FemModel& m = *model_;
  const int n = m.num_dofs();
  const int cols = 3 * static_cast<int>(points.size());
  Eigen::MatrixXd jt = Eigen::MatrixXd::Zero(n, cols);  // J^T
  for (size_t p = 0; p < points.size(); ++p) {
    const TetLocation& loc = points[p];
    if (loc.tet < 0 || loc.tet >= m.rest_mesh.num_tets() || !loc.weights.allFinite()) {
      std::ostringstream os;
      os << m.settings.body_name << ": constrained point " << p << " is bound to tet " << loc.tet << " (mesh has "
         << m.rest_mesh.num_tets() << " tets) or has non-finite weights";
      throw FemError(os.str());
    }
    // Barycentric: they sum to 1; slightly negative ones (a point just outside its tet,
    // LocateInTetMesh) are fine, but a point far from its tet is a caller's mistake.
    if (std::abs(loc.weights.sum() - 1.0) > 1e-6 || loc.weights.cwiseAbs().maxCoeff() > kMaxBarycentricWeight) {
      std::ostringstream os;
      os << m.settings.body_name << ": constrained point " << p << " has weights (" << loc.weights.transpose()
         << ") in tet " << loc.tet << ": barycentric weights sum to 1 and stay within +-" << kMaxBarycentricWeight;
      throw FemError(os.str());
    }
    for (int k = 0; k < 4; ++k)
      for (int axis = 0; axis < 3; ++axis) {
        const int dof = 3 * m.rest_mesh.tets(loc.tet, k) + axis;
        jt(dof, 3 * p + axis) += loc.weights[k] * m.free_dofs[dof];  // fixed dofs do not move
      }
  }
  if (!work_->system_assembled) AssembleSystem(state_.displacement_m);
  PointCompliance c;
  c.response.resize(n, cols);
  for (int j = 0; j < cols; ++j) {
    Eigen::VectorXd x;
    work_->last_increment.setZero();
    work_->extrapolation.Clear();
    // Accurate solves: the contact solver needs C itself, not a 20-iteration estimate.
    if (!SolveSystem(jt.col(j), x, 1e-12, 10 * n, nullptr))
      throw FemError(m.settings.body_name + ": compliance solve failed (system not positive definite, or non-finite)");
    c.response.col(j) = x;
  }
  work_->last_increment.setZero();
  work_->extrapolation.Clear();
  c.delassus = jt.transpose() * c.response;
  if (!c.delassus.allFinite()) throw FemError(m.settings.body_name + ": compliance is not finite");
  return c;
}

}  // namespace vesica::physics
