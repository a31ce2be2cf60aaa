#include "physics/fem/rotated_factor_preconditioner.h"

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/local_block_correction.h"
#include "physics/fem/pcg_solver.h"

namespace vesica::physics {

void RotatedFactorPreconditioner::ApplyTurnedFactor(const RotatedFactorParts& parts, const Eigen::VectorXd& r,
                                                    Eigen::VectorXd& z) {
  const std::vector<Eigen::Matrix3d>& rotations = *parts.node_rotations;
  if (parts.single_precision) {
    parts.rest_factor->SolveSinglePrecisionTurned(rotations, r, z);
    return;
  }
  const auto nodes = static_cast<Eigen::Index>(rotations.size());
  turned_residual_.resize(r.size());
  for (Eigen::Index n = 0; n < nodes; ++n)
    turned_residual_.segment<3>(3 * n) = rotations[n].transpose() * r.segment<3>(3 * n);
  parts.rest_factor->Solve(turned_residual_, turned_solution_);
  z.resize(r.size());
  for (Eigen::Index n = 0; n < nodes; ++n) z.segment<3>(3 * n) = rotations[n] * turned_solution_.segment<3>(3 * n);
}

void RotatedFactorPreconditioner::ForwardSweepFromZero(const RotatedFactorParts& parts, const Eigen::VectorXd& r,
                                                       Eigen::VectorXd& x, Eigen::VectorXd& upper_times_x) const {
  if (parts.float_rows)
    ForwardSweepFromZeroAndUpperTimes(*parts.float_rows, *parts.inverse_diagonal, r, x, upper_times_x);
  else
    ForwardSweepFromZeroAndUpperTimes(*parts.pattern, *parts.system_values, *parts.inverse_diagonal, r, x,
                                      upper_times_x);
}

void RotatedFactorPreconditioner::Apply(const RotatedFactorParts& parts, const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  const bool local = parts.local && !parts.local->empty();
  if (parts.sweeps == 0 && !local) {
    ApplyTurnedFactor(parts, r, z);
    return;
  }
  // residual_ follows z's residual r - S z through the forward sweeps and the first local solve.
  if (parts.sweeps > 0) {
    // A forward sweep from zero adds delta = (D + L)^-1 r and leaves r - S delta = -U delta from
    // the same pass; each further sweep starts from the residual the previous one left.
    ForwardSweepFromZero(parts, r, z, residual_);
    for (int sweep = 1; sweep < parts.sweeps; ++sweep) {
      sweep_residual_ = -residual_;
      ForwardSweepFromZero(parts, sweep_residual_, correction_, residual_);
      z += correction_;
    }
    residual_ = -residual_;
  } else {
    z.setZero(r.size());
    residual_ = r;
  }
  if (local) parts.local->Apply(residual_, z);
  ApplyTurnedFactor(parts, residual_, correction_);
  z += correction_;
  if (local) parts.local->ApplyAfter(residual_, correction_, z);
  for (int sweep = 0; sweep < parts.sweeps; ++sweep) {
    if (parts.float_rows)
      BlockGaussSeidelSweep(*parts.float_rows, *parts.inverse_diagonal, r, z, false);
    else
      BlockGaussSeidelSweep(*parts.pattern, *parts.system_values, *parts.inverse_diagonal, r, z, false);
  }
}

}  // namespace vesica::physics
