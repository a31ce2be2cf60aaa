#pragma once
// Run-time part of the capacitance matrix algorithm (gallbladder paper eqs. 3-4). Instrument
// contacts turn s free nodes into displacement-prescribed ones; instead of refactoring the
// 3n x 3n system, the s-block capacitance matrix C = Xi_cc (the reference compliance between the
// contact nodes) is formed and factored once per contact set (Sherman-Morrison-Woodbury), after
// which
//   contact tractions   t_c = C^{-1} (u_c - u_ref,c)                     O(s^2)
//   all unknowns        Y   = Y_ref + Xi[:, contact] t_c                  O(n s)
// with Y_ref the response to the applied (spring) tractions. Reads the model; never changes it.
// The const queries use internal scratch buffers (no allocation per call): one thread at a time
// per solver; give the haptic thread its own solver on the same model.

#include <Eigen/Core>
#include <Eigen/LU>
#include <span>
#include <vector>

#include "physics/bem/bem_model.h"

namespace vesica::physics {

/// Surface state of the BEM body after a solve.
struct BemSolution {
  Vertices displacement_m;  ///< #V x 3; zero on the fixed region
  Vertices traction_Pa;     ///< #V x 3; reactions on the fixed region, applied + contact elsewhere
};

class BemCapacitanceSolver {
 public:
  /// `model` must outlive the solver.
  explicit BemCapacitanceSolver(const BemModel& model);

  /// Nodes with prescribed displacement from now on (distinct free vertices; empty = none). Forms
  /// and factors the capacitance matrix. Throws BemError for an index out of range, a fixed
  /// vertex or a repeated one, SingularSystemError when the capacitance matrix is singular.
  void SetContactNodes(std::span<const int> nodes);
  const std::vector<int>& contact_nodes() const { return contact_nodes_; }

  /// Applied tractions (Pa), one row per listed free vertex; replaces earlier ones. O(n k).
  void SetAppliedTractions(std::span<const int> nodes, const Vertices& tractions_Pa);

  /// Haptic-rate query, O(s^2): tractions (Pa) at the contact nodes, s x 3, for their prescribed
  /// displacements (m), s x 3 in the order given to SetContactNodes.
  void ContactTractions(const Vertices& contact_displacements_m, Vertices& contact_tractions_Pa) const;

  /// Nodal contact forces (N) = contact tractions times the nodes' lumped areas; O(s^2).
  void ContactForces(const Vertices& contact_displacements_m, Vertices& contact_forces_N) const;

  /// Global deformation: every node's displacement and traction, O(n s). `out` is resized once.
  void Solve(const Vertices& contact_displacements_m, BemSolution& out) const;

  /// The contact compliance (m/Pa), 3s x 3s: u_c = C t_c.
  const Eigen::MatrixXd& capacitance() const { return capacitance_; }

 private:
  void CheckContactDisplacements(const Vertices& u) const;
  void SolveContactTraction(const Vertices& contact_displacements_m) const;  // -> contact_traction_

  const BemModel* model_;
  std::vector<int> contact_nodes_;
  Eigen::MatrixXd capacitance_;             // 3s x 3s
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_lu_;
  Eigen::MatrixXd contact_columns_;         // Xi[:, contact dofs], 3#V x 3s
  Eigen::VectorXd reference_response_;      // Y_ref, 3#V
  Eigen::VectorXd applied_traction_;        // 3#V (zero except applied nodes)
  mutable Eigen::VectorXd rhs_, contact_traction_, unknowns_;
};

}  // namespace vesica::physics
