#pragma once
// The capacitance matrix algorithm (gallbladder paper eqs. 3-4) with a tool's footprint as a few
// traction modes (tool_footprint.h) instead of one prescribed node per covered vertex (issue 37).
// The unknowns are the modes' amplitudes alpha (N), m = 3 x #shapes whatever the mesh; the
// constraint is that each mode's work-conjugate displacement, delta_k = sum_i w_ik u_i . e_ck (the
// p-weighted mean displacement of the footprint), equals what a rigid tool translated by d gives
// it: resultant_k d . e_ck. With the mode compliance C_kl = delta_k of mode l's unit amplitude:
//   alpha = C^{-1} b(d)                       O(m^2)   the haptic query
//   u     = sum_l alpha_l Xi tau_l            O(n m)   the global deformation
// Reads the model; never changes it. One thread at a time per solver (scratch buffers).

#include <Eigen/Core>
#include <Eigen/LU>

#include "physics/bem/bem_model.h"
#include "physics/bem/capacitance_solver.h"
#include "physics/bem/tool_footprint.h"

namespace vesica::physics {

class BemFootprintSolver {
 public:
  /// `model` must outlive the solver.
  explicit BemFootprintSolver(const BemModel& model);

  /// The tool's footprint from now on: forms the modes' responses (O(n q m), q loaded nodes) and
  /// factors their compliance. Throws BemError when a loaded node is out of range or every one is
  /// fixed, SingularSystemError when the mode compliance is singular (e.g. two equal shapes).
  void SetFootprint(const FootprintModes& modes);
  const FootprintModes& footprint() const { return modes_; }

  /// Haptic-rate query, O(m^2): the total force (N) the tool applies to the tissue when it is
  /// translated by `tool_displacement_m` from the rest surface, footprint stuck to it.
  Eigen::Vector3d ContactForce(const Eigen::Vector3d& tool_displacement_m) const;

  /// Global deformation, O(n m): every node's displacement and traction (the footprint's modes'
  /// tractions on the loaded nodes, reactions on the fixed region).
  void Solve(const Eigen::Vector3d& tool_displacement_m, BemSolution& out) const;

  /// The modes' compliance (m/N), m x m.
  const Eigen::MatrixXd& mode_compliance() const { return compliance_; }

 private:
  void SolveAmplitudes(const Eigen::Vector3d& tool_displacement_m) const;  // -> amplitudes_

  const BemModel* model_;
  FootprintModes modes_;
  Eigen::MatrixXd mode_columns_;  // 3#V x m: the reference unknowns' response to each mode
  Eigen::MatrixXd compliance_;    // m x m
  Eigen::PartialPivLU<Eigen::MatrixXd> compliance_lu_;
  mutable Eigen::VectorXd rhs_, amplitudes_;
};

}  // namespace vesica::physics
