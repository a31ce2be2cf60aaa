#pragma once
// Small-strain equilibrium K u = f with Dirichlet dofs (the reference the BEM liver is checked
// against, and the cantilever/patch validations).

#include <Eigen/Core>

#include "physics/fem/fem_model.h"

namespace vesica::physics {

/// Returns u (3n, m) with K_ff u_f = f_f - K_fd u_d and u_d = prescribed at the model's fixed dofs
/// (prescribed: 3n, only its fixed entries are read; empty means zero). Uses the linear K whatever
/// the element model. Throws FemError naming the body when there are no fixed dofs, sizes differ,
/// values are not finite, or the fixed dofs leave a rigid motion free (K_ff singular).
Eigen::VectorXd SolveLinearStatics(const FemModel& model, const Eigen::VectorXd& force_N,
                                   const Eigen::VectorXd& prescribed_m = Eigen::VectorXd());

}  // namespace vesica::physics
