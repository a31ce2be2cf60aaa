#include "physics/fem/linear_statics.h"

#include <algorithm>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_error.h"

namespace vesica::physics {

namespace {

// True when the fixed dofs block all six rigid motions: the rigid modes (3 translations,
// 3 rotations about the centroid, arms scaled by the body's size) restricted to the fixed dofs
// must have full rank. CHOLMOD alone cannot tell: round-off makes a singular K look positive.
bool FixedDofsRemoveRigidMotions(const FemModel& m) {
  const Vertices& x = m.rest_mesh.vertices;
  const Eigen::RowVector3d centre = x.colwise().mean();
  const double size = std::max((x.colwise().maxCoeff() - x.colwise().minCoeff()).maxCoeff(), 1e-300);
  Eigen::Matrix<double, 6, 6> gram = Eigen::Matrix<double, 6, 6>::Zero();
  for (int dof : m.fixed_dofs) {
    const int axis = dof % 3;
    const Eigen::Vector3d r = (x.row(dof / 3) - centre).transpose() / size;
    Eigen::Matrix<double, 6, 1> row = Eigen::Matrix<double, 6, 1>::Zero();
    row[axis] = 1.0;
    // Component `axis` of omega x r for unit omega along each axis.
    for (int w = 0; w < 3; ++w) row[3 + w] = Eigen::Vector3d::Unit(w).cross(r)[axis];
    gram += row * row.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(gram);
  return eig.eigenvalues()[0] > 1e-10 * eig.eigenvalues()[5];
}

}  // namespace

Eigen::VectorXd SolveLinearStatics(const FemModel& m, const Eigen::VectorXd& f, const Eigen::VectorXd& prescribed) {
  const std::string& name = m.settings.body_name;
  const int n = m.num_dofs();
  if (m.fixed_dofs.empty())
    throw FemError(name + ": linear statics needs fixed nodes, none were given (the body could move rigidly)");
  if (!FixedDofsRemoveRigidMotions(m))
    throw FemError(name + ": the fixed nodes leave a rigid motion free (statics needs at least 3 non-collinear fixed nodes or equivalent)");
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
