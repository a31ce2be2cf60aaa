#include "physics/scene/fem_rest_compliance.h"

#include <string>

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/fem_error.h"
#include "physics/fem/time_integrator.h"

namespace vesica::physics {

struct FemRestCompliance::Impl {
  std::shared_ptr<const FemModel> model;
  Eigen::VectorXd attachment_stiffness, attachment_damping;
  CholmodSolver cholmod;
  bool factor_valid = false;
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 3>> columns;  // per node; empty = not computed
};

FemRestCompliance::FemRestCompliance(std::shared_ptr<const FemModel> model) : impl_(std::make_unique<Impl>()) {
  if (!model) throw FemError("FemRestCompliance: null model");
  impl_->model = std::move(model);
  const int n = impl_->model->num_dofs();
  impl_->attachment_stiffness.setZero(n);
  impl_->attachment_damping.setZero(n);
  impl_->columns.resize(static_cast<size_t>(impl_->model->num_nodes()));
}
FemRestCompliance::~FemRestCompliance() = default;

void FemRestCompliance::SetAttachments(const Eigen::VectorXd& k, const Eigen::VectorXd& c) {
  const FemModel& m = *impl_->model;
  if (k.size() != m.num_dofs() || c.size() != m.num_dofs() || !k.allFinite() || !c.allFinite() || k.minCoeff() < 0.0 ||
      c.minCoeff() < 0.0)
    throw FemError(m.settings.body_name + ": attachment stiffness/damping must be 3 x " +
                   std::to_string(m.num_nodes()) + " finite entries >= 0");
  impl_->attachment_stiffness = k;
  impl_->attachment_damping = c;
  impl_->factor_valid = false;
  for (auto& col : impl_->columns) col.resize(0, 3);
}

const Eigen::Matrix<double, Eigen::Dynamic, 3>& FemRestCompliance::NodeColumns(int node) {
  Impl& w = *impl_;
  const FemModel& m = *w.model;
  if (node < 0 || node >= m.num_nodes())
    throw FemError(m.settings.body_name + ": compliance asked for node " + std::to_string(node) + " of " +
                   std::to_string(m.num_nodes()));
  if (!w.factor_valid) {
    const FemSettings& s = m.settings;
    const SystemCoefficients c = IntegratorCoefficients(s);
    Eigen::VectorXd values = (1.0 + c.damping * s.rayleigh_stiffness_s) * m.linear_stiffness_values;
    const double mass_scale = c.mass + c.damping * s.rayleigh_mass_per_s;
    if (m.uses_consistent_mass()) {
      values += mass_scale * m.consistent_mass_values;
    } else {
      for (int i = 0; i < m.num_dofs(); ++i) values[m.pattern.diagonal_slot[i]] += mass_scale * m.lumped_mass_kg[i];
    }
    for (int i = 0; i < m.num_dofs(); ++i)
      values[m.pattern.diagonal_slot[i]] += w.attachment_stiffness[i] + c.damping * w.attachment_damping[i];
    for (int k : m.constrained_slots) values[k] = 0.0;
    for (int i : m.fixed_dofs) values[m.pattern.diagonal_slot[i]] = 1.0;
    if (!w.cholmod.Factorize(m.pattern, values))
      throw FemError(m.settings.body_name +
                     ": rest system matrix for the constraint compliance is not positive definite");
    w.factor_valid = true;
    ++factorizations_;
  }
  auto& col = w.columns[static_cast<size_t>(node)];
  if (col.rows() == 0) {
    col.resize(m.num_dofs(), 3);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m.num_dofs()), x;
    for (int axis = 0; axis < 3; ++axis) {
      const int dof = 3 * node + axis;
      if (m.free_dofs[dof] == 0.0) {  // a fixed dof does not move under any force
        col.col(axis).setZero();
        continue;
      }
      e[dof] = 1.0;
      w.cholmod.Solve(e, x);
      e[dof] = 0.0;
      col.col(axis) = x.cwiseProduct(m.free_dofs);
    }
  }
  return col;
}

}  // namespace vesica::physics
