#include "physics/fem/linear_statics.h"

#include <sstream>

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_error.h"

namespace vesica::physics {

Eigen::VectorXd SolveLinearStatics(const FemModel& m, const Eigen::VectorXd& f, const Eigen::VectorXd& prescribed) {
  const std::string& name = m.settings.body_name;
  const int n = m.num_dofs();
  if (m.fixed_dofs.empty())
    throw FemError(name + ": linear statics needs fixed nodes, none were given (the body could move rigidly)");
  if (f.size() != n || (prescribed.size() != 0 && prescribed.size() != n)) {
    std::ostringstream os;
    os << name << ": linear statics got force of size " << f.size() << " and prescribed displacement of size "
       << prescribed.size() << ", expected " << n;
    throw FemError(os.str());
  }
  if (!f.allFinite() || !prescribed.allFinite()) throw FemError(name + ": linear statics got non-finite input");

  Eigen::VectorXd u_d = Eigen::VectorXd::Zero(n);
  if (prescribed.size() == n)
    for (int i : m.fixed_dofs) u_d[i] = prescribed[i];
  Eigen::VectorXd k_ud;
  SymmetricPatternMultiply(m.pattern, m.linear_stiffness_values, u_d, k_ud);
  Eigen::VectorXd rhs = f - k_ud;
  for (int i : m.fixed_dofs) rhs[i] = 0.0;

  Eigen::VectorXd k = m.linear_stiffness_values;
  for (int s : m.constrained_slots) k[s] = 0.0;
  for (int i : m.fixed_dofs) k[m.pattern.diagonal_slot[i]] = 1.0;
  CholmodSolver cholesky;
  if (!cholesky.Factorize(m.pattern, k))
    throw FemError(name + ": stiffness is singular: the fixed nodes leave a rigid motion free");
  Eigen::VectorXd u;
  cholesky.Solve(rhs, u);
  for (int i : m.fixed_dofs) u[i] = u_d[i];
  return u;
}

}  // namespace vesica::physics
