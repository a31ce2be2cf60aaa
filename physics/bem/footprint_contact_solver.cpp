#include "physics/bem/footprint_contact_solver.h"

#include <string>

#include "physics/bem/bem_errors.h"

namespace vesica::physics {

BemFootprintSolver::BemFootprintSolver(const BemModel& model) : model_(&model) {}

void BemFootprintSolver::SetFootprint(const FootprintModes& modes) {
  const int n = model_->num_nodes();
  const Eigen::Index q = static_cast<Eigen::Index>(modes.nodes.size());
  const Eigen::Index num_shapes = static_cast<Eigen::Index>(modes.shapes.size());
  if (modes.load_weights.rows() != q || modes.traction_per_N.rows() != q || modes.load_weights.cols() != num_shapes ||
      modes.traction_per_N.cols() != num_shapes || modes.resultant.size() != num_shapes || num_shapes == 0)
    throw BemError("BEM footprint: modes' sizes disagree (" + std::to_string(q) + " nodes, " +
                   std::to_string(num_shapes) + " shapes)");
  bool any_free = false;
  for (int node : modes.nodes) {
    if (node < 0 || node >= n)
      throw BemError("BEM footprint node " + std::to_string(node) + ": out of range [0, " + std::to_string(n) + ")");
    any_free = any_free || model_->layout.free_index(node) >= 0;
  }
  if (!any_free) throw BemError("BEM footprint: every loaded node lies in the fixed region");

  const Eigen::Index m = 3 * num_shapes;
  Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(3 * n, m);
  for (Eigen::Index j = 0; j < q; ++j) {
    const int fj = model_->layout.free_index(modes.nodes[static_cast<std::size_t>(j)]);
    if (fj < 0) continue;  // a traction on the fixed region moves nothing
    for (Eigen::Index s = 0; s < num_shapes; ++s)
      columns.middleCols<3>(3 * s).noalias() += modes.traction_per_N(j, s) * model_->greens.middleCols<3>(3 * fj);
  }
  // delta_k = sum_i w_i(s_k) u_i . e_ck over free loaded nodes (a fixed node does not move).
  Eigen::MatrixXd compliance = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index i = 0; i < q; ++i) {
    const int node = modes.nodes[static_cast<std::size_t>(i)];
    if (model_->layout.free_index(node) < 0) continue;
    for (Eigen::Index s = 0; s < num_shapes; ++s)
      compliance.middleRows<3>(3 * s) += modes.load_weights(i, s) * columns.middleRows<3>(3 * node);
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(compliance);
  const double rcond = lu.rcond();
  if (!(rcond > 1e-12))
    throw SingularSystemError("BEM footprint of " + std::to_string(num_shapes) +
                              " traction shapes: mode compliance singular (reciprocal condition " +
                              std::to_string(rcond) + ")");
  modes_ = modes;
  mode_columns_ = std::move(columns);
  compliance_ = std::move(compliance);
  compliance_lu_ = std::move(lu);
  rhs_.resize(m);
  amplitudes_.resize(m);
}

void BemFootprintSolver::SolveAmplitudes(const Eigen::Vector3d& tool_displacement_m) const {
  if (modes_.shapes.empty()) throw BemError("BEM footprint: no footprint set");
  if (!tool_displacement_m.allFinite()) throw BemError("BEM footprint: tool displacement not finite");
  for (Eigen::Index s = 0; s < static_cast<Eigen::Index>(modes_.shapes.size()); ++s)
    rhs_.segment<3>(3 * s) = modes_.resultant(s) * tool_displacement_m;
  amplitudes_ = compliance_lu_.solve(rhs_);
}

Eigen::Vector3d BemFootprintSolver::ContactForce(const Eigen::Vector3d& tool_displacement_m) const {
  SolveAmplitudes(tool_displacement_m);
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (Eigen::Index s = 0; s < static_cast<Eigen::Index>(modes_.shapes.size()); ++s)
    force += modes_.resultant(s) * amplitudes_.segment<3>(3 * s);
  return force;
}

void BemFootprintSolver::Solve(const Eigen::Vector3d& tool_displacement_m, BemSolution& out) const {
  SolveAmplitudes(tool_displacement_m);
  const int n = model_->num_nodes();
  out.displacement_m.resize(n, 3);
  out.traction_Pa.resize(n, 3);
  auto u = AsStackedVector(out.displacement_m);
  auto t = AsStackedVector(out.traction_Pa);
  t.setZero();
  for (int i = 0; i < n; ++i) {
    const bool free = model_->layout.free_index(i) >= 0;
    const Eigen::Vector3d y = mode_columns_.middleRows<3>(3 * i) * amplitudes_;
    u.segment<3>(3 * i) = free ? y : Eigen::Vector3d::Zero();
    if (!free) t.segment<3>(3 * i) = y;
  }
  for (std::size_t j = 0; j < modes_.nodes.size(); ++j) {
    const int node = modes_.nodes[j];
    if (model_->layout.free_index(node) < 0) continue;
    for (Eigen::Index s = 0; s < static_cast<Eigen::Index>(modes_.shapes.size()); ++s)
      t.segment<3>(3 * node) += modes_.traction_per_N(static_cast<Eigen::Index>(j), s) * amplitudes_.segment<3>(3 * s);
  }
}

}  // namespace vesica::physics
