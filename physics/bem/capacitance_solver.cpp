#include "physics/bem/capacitance_solver.h"

#include <string>

#include "physics/bem/bem_errors.h"

namespace vesica::physics {

BemCapacitanceSolver::BemCapacitanceSolver(const BemModel& model) : model_(&model) {
  const Eigen::Index dofs = 3 * model.num_nodes();
  reference_response_ = Eigen::VectorXd::Zero(dofs);
  applied_traction_ = Eigen::VectorXd::Zero(dofs);
  unknowns_.resize(dofs);
  SetContactNodes({});
}

void BemCapacitanceSolver::SetContactNodes(std::span<const int> nodes) {
  const int n = model_->num_nodes();
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const int node = nodes[k];
    const std::string where = "BEM contact node " + std::to_string(node) + " (entry " +
                              std::to_string(k) + ")";
    if (node < 0 || node >= n)
      throw BemError(where + ": out of range [0, " + std::to_string(n) + ")");
    if (model_->layout.free_index(node) < 0)
      throw BemError(where + ": lies in the fixed region, its displacement is already zero");
    if (seen[static_cast<std::size_t>(node)]++)
      throw SingularSystemError(where + ": listed twice, the capacitance matrix would be singular");
  }
  const Eigen::Index s3 = 3 * static_cast<Eigen::Index>(nodes.size());
  Eigen::MatrixXd columns(3 * n, s3);
  for (std::size_t k = 0; k < nodes.size(); ++k)
    columns.middleCols<3>(3 * static_cast<Eigen::Index>(k)) =
        model_->greens.middleCols<3>(3 * model_->layout.free_index(nodes[k]));
  Eigen::MatrixXd capacitance(s3, s3);
  for (std::size_t k = 0; k < nodes.size(); ++k)
    capacitance.middleRows<3>(3 * static_cast<Eigen::Index>(k)) = columns.middleRows<3>(3 * nodes[k]);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  if (s3 > 0) {
    lu.compute(capacitance);
    const double rcond = lu.rcond();
    if (!(rcond > 1e-12))
      throw SingularSystemError("BEM contact set of " + std::to_string(nodes.size()) +
                                " nodes: capacitance matrix singular (reciprocal condition " +
                                std::to_string(rcond) + ")");
  }
  // Commit only after every check passed: a rejected set leaves the previous one in place.
  contact_nodes_.assign(nodes.begin(), nodes.end());
  contact_columns_ = std::move(columns);
  capacitance_ = std::move(capacitance);
  capacitance_lu_ = std::move(lu);
  rhs_.resize(s3);
  contact_traction_.resize(s3);
}

void BemCapacitanceSolver::SetAppliedTractions(std::span<const int> nodes,
                                               const Vertices& tractions_Pa) {
  const int n = model_->num_nodes();
  if (tractions_Pa.rows() != static_cast<Eigen::Index>(nodes.size()))
    throw BemError("BEM applied tractions: " + std::to_string(tractions_Pa.rows()) + " rows for " +
                   std::to_string(nodes.size()) + " nodes");
  Eigen::VectorXd applied = Eigen::VectorXd::Zero(3 * n);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const int node = nodes[k];
    const std::string where = "BEM applied traction node " + std::to_string(node);
    if (node < 0 || node >= n) throw BemError(where + ": out of range");
    if (model_->layout.free_index(node) < 0) throw BemError(where + ": lies in the fixed region");
    if (!tractions_Pa.row(static_cast<Eigen::Index>(k)).allFinite())
      throw BemError(where + ": traction not finite");
    applied.segment<3>(3 * node) += tractions_Pa.row(static_cast<Eigen::Index>(k)).transpose();
  }
  Eigen::VectorXd response = Eigen::VectorXd::Zero(3 * n);
  for (std::size_t k = 0; k < nodes.size(); ++k)
    response.noalias() += model_->greens.middleCols<3>(3 * model_->layout.free_index(nodes[k])) *
                          tractions_Pa.row(static_cast<Eigen::Index>(k)).transpose();
  applied_traction_ = std::move(applied);
  reference_response_ = std::move(response);
}

void BemCapacitanceSolver::CheckContactDisplacements(const Vertices& u) const {
  if (u.rows() != static_cast<Eigen::Index>(contact_nodes_.size()))
    throw BemError("BEM contact displacements: " + std::to_string(u.rows()) + " rows for " +
                   std::to_string(contact_nodes_.size()) + " contact nodes");
  if (!u.allFinite()) throw BemError("BEM contact displacements: not finite");
}

void BemCapacitanceSolver::SolveContactTraction(const Vertices& contact_displacements_m) const {
  CheckContactDisplacements(contact_displacements_m);
  const Eigen::Index s = static_cast<Eigen::Index>(contact_nodes_.size());
  for (Eigen::Index k = 0; k < s; ++k)
    rhs_.segment<3>(3 * k) = contact_displacements_m.row(k).transpose() -
                             reference_response_.segment<3>(3 * contact_nodes_[static_cast<std::size_t>(k)]);
  if (s > 0) contact_traction_ = capacitance_lu_.solve(rhs_);
}

void BemCapacitanceSolver::ContactTractions(const Vertices& contact_displacements_m,
                                            Vertices& contact_tractions_Pa) const {
  SolveContactTraction(contact_displacements_m);
  contact_tractions_Pa.resize(static_cast<Eigen::Index>(contact_nodes_.size()), 3);
  AsStackedVector(contact_tractions_Pa) = contact_traction_;
}

void BemCapacitanceSolver::ContactForces(const Vertices& contact_displacements_m,
                                         Vertices& contact_forces_N) const {
  ContactTractions(contact_displacements_m, contact_forces_N);
  for (std::size_t k = 0; k < contact_nodes_.size(); ++k)
    contact_forces_N.row(static_cast<Eigen::Index>(k)) *= model_->lumped_area_m2(contact_nodes_[k]);
}

void BemCapacitanceSolver::Solve(const Vertices& contact_displacements_m, BemSolution& out) const {
  SolveContactTraction(contact_displacements_m);
  unknowns_ = reference_response_;
  if (!contact_nodes_.empty()) unknowns_.noalias() += contact_columns_ * contact_traction_;

  const int n = model_->num_nodes();
  out.displacement_m.resize(n, 3);
  out.traction_Pa.resize(n, 3);
  auto u = AsStackedVector(out.displacement_m);
  auto t = AsStackedVector(out.traction_Pa);
  t = applied_traction_;
  for (int i = 0; i < n; ++i) {
    if (model_->layout.free_index(i) >= 0) {
      u.segment<3>(3 * i) = unknowns_.segment<3>(3 * i);
    } else {
      u.segment<3>(3 * i).setZero();
      t.segment<3>(3 * i) = unknowns_.segment<3>(3 * i);
    }
  }
  for (std::size_t k = 0; k < contact_nodes_.size(); ++k) {
    // A contact node's displacement is the prescribed one (equal up to round-off).
    u.segment<3>(3 * contact_nodes_[k]) = contact_displacements_m.row(static_cast<Eigen::Index>(k)).transpose();
    t.segment<3>(3 * contact_nodes_[k]) += contact_traction_.segment<3>(3 * static_cast<Eigen::Index>(k));
  }
}

}  // namespace vesica::physics
