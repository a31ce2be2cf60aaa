#include "physics/scene/fem_rest_compliance.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <string>
#include <utility>
#include <vector>

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/fem_error.h"
#include "physics/fem/time_integrator.h"

namespace vesica::physics {

namespace {
void CheckAttachments(const FemModel& m, const Eigen::VectorXd& k, const Eigen::VectorXd& c) {
  if (k.size() != m.num_dofs() || c.size() != m.num_dofs() || !k.allFinite() || !c.allFinite() || k.minCoeff() < 0.0 ||
      c.minCoeff() < 0.0)
    throw FemError(m.settings.body_name + ": attachment stiffness/damping must be 3 x " +
                   std::to_string(m.num_nodes()) + " finite entries >= 0");
}

// S0 = c_M M + c_D D + K0 + attachments, in pattern order, fixed dofs decoupled.
Eigen::VectorXd RestSystemValues(const FemModel& m, const Eigen::VectorXd& k, const Eigen::VectorXd& c_att) {
  const FemSettings& s = m.settings;
  const SystemCoefficients c = IntegratorCoefficients(s);
  Eigen::VectorXd values = (1.0 + c.damping * s.rayleigh_stiffness_s) * m.linear_stiffness_values;
  const double mass_scale = c.mass + c.damping * s.rayleigh_mass_per_s;
  if (m.uses_consistent_mass()) {
    values += mass_scale * m.consistent_mass_values;
  } else {
    for (int i = 0; i < m.num_dofs(); ++i) values[m.pattern.diagonal_slot[i]] += mass_scale * m.lumped_mass_kg[i];
  }
  for (int i = 0; i < m.num_dofs(); ++i) values[m.pattern.diagonal_slot[i]] += k[i] + c.damping * c_att[i];
  for (int slot : m.constrained_slots) values[slot] = 0.0;
  for (int i : m.fixed_dofs) values[m.pattern.diagonal_slot[i]] = 1.0;
  return values;
}

FemError NotPositiveDefinite(const FemModel& m) {
  return FemError(m.settings.body_name + ": rest system matrix for the constraint compliance is not positive definite");
}

std::shared_ptr<const CholmodSolver> FactorizeRestSystem(const FemModel& m, const Eigen::VectorXd& values) {
  auto solver = std::make_shared<CholmodSolver>();
  if (!solver->Factorize(m.pattern, values)) throw NotPositiveDefinite(m);
  return solver;
}
using NodeBlock = Eigen::Matrix<double, Eigen::Dynamic, 3>;

// Column block of S0^-1 for unit forces spread over weighted nodes (fixed dofs: zero).
NodeBlock SolveLoadColumns(const FemModel& m, const CholmodSolver& cholmod,
                           const std::vector<std::pair<int, double>>& points) {
  // One solve with the three right-hand sides: it reads the factor once, not three times.
  NodeBlock unit = NodeBlock::Zero(m.num_dofs(), 3);
  for (const auto& [node, weight] : points)
    for (int axis = 0; axis < 3; ++axis) unit(3 * node + axis, axis) += weight;
  for (int axis = 0; axis < 3; ++axis)
    unit.col(axis) = unit.col(axis).cwiseProduct(m.free_dofs);  // no force on a fixed dof
  NodeBlock col;
  cholmod.Solve(unit, col);
  for (int axis = 0; axis < 3; ++axis) col.col(axis) = col.col(axis).cwiseProduct(m.free_dofs);  // nor motion
  return col;
}

// Column block of S0^-1 for unit forces on the node's three dofs (fixed dofs: zero).
NodeBlock SolveNodeColumns(const FemModel& m, const CholmodSolver& cholmod, int node) {
  // One solve with the three right-hand sides: it reads the factor once, not three times.
  NodeBlock unit = NodeBlock::Zero(m.num_dofs(), 3);
  for (int axis = 0; axis < 3; ++axis) unit(3 * node + axis, axis) = 1.0;
  NodeBlock col;
  cholmod.Solve(unit, col);
  for (int axis = 0; axis < 3; ++axis) {
    if (m.free_dofs[3 * node + axis] == 0.0)
      col.col(axis).setZero();  // a fixed dof does not move under any force
    else
      col.col(axis) = col.col(axis).cwiseProduct(m.free_dofs);
  }
  return col;
}

// What the worker of BeginAttachments hands back: the factor and the columns of the nodes asked
// for since the Begin before (the grasped tet, the hook's contact: usually still in use).
struct Refactored {
  std::shared_ptr<const CholmodSolver> cholmod;
  std::vector<std::pair<int, NodeBlock>> columns;
};
}  // namespace

struct FemRestCompliance::Impl {
  std::shared_ptr<const FemModel> model;
  Eigen::VectorXd attachment_stiffness, attachment_damping;
  std::shared_ptr<const CholmodSolver> cholmod;  // null until the first factorisation
  bool factor_valid = false;
  std::vector<NodeBlock> columns;  // per node; empty = not computed
  std::vector<char> asked;         // per node: columns asked for since the last BeginAttachments
  // BeginAttachments: the attachments and the factorisation running on a worker thread.
  Eigen::VectorXd pending_stiffness, pending_damping;
  std::future<Refactored> pending;
};

FemRestCompliance::FemRestCompliance(std::shared_ptr<const FemModel> model) : impl_(std::make_unique<Impl>()) {
  if (!model) throw FemError("FemRestCompliance: null model");
  impl_->model = std::move(model);
  const int n = impl_->model->num_dofs();
  impl_->attachment_stiffness.setZero(n);
  impl_->attachment_damping.setZero(n);
  impl_->columns.resize(static_cast<size_t>(impl_->model->num_nodes()));
  impl_->asked.assign(static_cast<size_t>(impl_->model->num_nodes()), 0);
}
FemRestCompliance::~FemRestCompliance() = default;

void FemRestCompliance::SetAttachments(const Eigen::VectorXd& k, const Eigen::VectorXd& c) {
  CheckAttachments(*impl_->model, k, c);
  if (impl_->pending.valid()) impl_->pending.wait();  // its result is superseded
  impl_->pending = {};
  impl_->attachment_stiffness = k;
  impl_->attachment_damping = c;
  for (auto& col : impl_->columns) col.resize(0, 3);
  // Now rather than at the first constraint: a scene sets its attachments before it runs, and the
  // ~30 ms then stay out of the step that grasps first.
  impl_->cholmod = FactorizeRestSystem(*impl_->model, RestSystemValues(*impl_->model, k, c));
  impl_->factor_valid = true;
  ++factorizations_;
}

void FemRestCompliance::BeginAttachments(const Eigen::VectorXd& k, const Eigen::VectorXd& c, RestFactorFuture shared) {
  CheckAttachments(*impl_->model, k, c);
  AdoptAttachments();
  Impl& w = *impl_;
  w.pending_stiffness = k;
  w.pending_damping = c;
  // The nodes constraints asked for lately (not every node ever cached: that list only grows).
  std::vector<int> in_use;
  for (size_t node = 0; node < w.asked.size(); ++node)
    if (w.asked[node]) in_use.push_back(static_cast<int>(node));
  std::fill(w.asked.begin(), w.asked.end(), 0);
  Eigen::VectorXd values;
  if (!shared.valid()) values = RestSystemValues(*w.model, k, c);
  w.pending = std::async(std::launch::async, [model = w.model, values = std::move(values), shared, in_use] {
    Refactored out{shared.valid() ? shared.get() : FactorizeRestSystem(*model, values), {}};
    if (!out.cholmod || !out.cholmod->factorized()) throw NotPositiveDefinite(*model);
    for (int node : in_use) out.columns.emplace_back(node, SolveNodeColumns(*model, *out.cholmod, node));
    return out;
  });
}

void FemRestCompliance::AdoptAttachments() {
  Impl& w = *impl_;
  if (!w.pending.valid()) return;
  Refactored done = w.pending.get();  // rethrows the worker's FemError
  w.cholmod = std::move(done.cholmod);
  w.attachment_stiffness = std::move(w.pending_stiffness);
  w.attachment_damping = std::move(w.pending_damping);
  w.factor_valid = true;
  ++factorizations_;
  for (auto& col : w.columns) col.resize(0, 3);
  for (auto& [node, col] : done.columns) w.columns[static_cast<size_t>(node)] = std::move(col);
}

bool FemRestCompliance::attachments_pending() const { return impl_->pending.valid(); }

Eigen::Matrix<double, Eigen::Dynamic, 3> FemRestCompliance::LoadColumns(
    const std::vector<std::pair<int, double>>& points) {
  Impl& w = *impl_;
  const FemModel& m = *w.model;
  for (const auto& [node, weight] : points)
    if (node < 0 || node >= m.num_nodes() || !std::isfinite(weight))
      throw FemError(m.settings.body_name + ": compliance asked for a load on node " + std::to_string(node) + " of " +
                     std::to_string(m.num_nodes()) + " (weight " + std::to_string(weight) + ")");
  if (!w.factor_valid) {
    w.cholmod = FactorizeRestSystem(m, RestSystemValues(m, w.attachment_stiffness, w.attachment_damping));
    w.factor_valid = true;
    ++factorizations_;
  }
  return SolveLoadColumns(m, *w.cholmod, points);
}

const Eigen::Matrix<double, Eigen::Dynamic, 3>& FemRestCompliance::NodeColumns(int node) {
  Impl& w = *impl_;
  const FemModel& m = *w.model;
  if (node < 0 || node >= m.num_nodes())
    throw FemError(m.settings.body_name + ": compliance asked for node " + std::to_string(node) + " of " +
                   std::to_string(m.num_nodes()));
  if (!w.factor_valid) {
    w.cholmod = FactorizeRestSystem(m, RestSystemValues(m, w.attachment_stiffness, w.attachment_damping));
    w.factor_valid = true;
    ++factorizations_;
  }
  w.asked[static_cast<size_t>(node)] = 1;
  auto& col = w.columns[static_cast<size_t>(node)];
  if (col.rows() == 0) col = SolveNodeColumns(m, *w.cholmod, node);
  return col;
}

}  // namespace vesica::physics
