#pragma once
// A tool's push on the BEM liver as the scene's constraint rows use it (issue 37): instead of a
// point force shared by the hit triangle's three vertices (lumped: the mesh's footprint, an
// element or two across, whatever the tool), the rigid-punch traction over the tool's own disc
// footprint (tool_footprint.h, shape kPunch): per newton of the row's force, nodal load weights
// (the work-conjugate weights of the footprint's mean displacement) and nodal tractions (their
// L2 projection onto the hat functions). On the study's hook load this is what brings the
// trainer's 1,001-vertex liver from 40 % to within 10 % of CalculiX (docs/fidelity.md).

#include <Eigen/Core>
#include <vector>

#include "physics/bem/bem_model.h"

namespace vesica::physics {

struct BemContactLoad {
  std::vector<int> nodes;          ///< q loaded vertices
  Eigen::VectorXd load_weights;    ///< q, sum 1: the row's displacement is sum_i w_i u_i
  Eigen::VectorXd traction_per_N;  ///< q, 1/m^2: nodal traction per newton of the row's force
};

/// The punch load of a disc of `radius_m` around the point with barycentric `weights` in
/// `triangle` of the model's rest surface, in the plane normal to `normal_W`. Throws BemError for
/// a triangle out of range, weights that are not barycentric, a radius not positive and finite.
BemContactLoad MakeToolContactLoad(const BemModel& model, int triangle, const Eigen::Vector3d& weights,
                                   const Eigen::Vector3d& normal_W, double radius_m);

/// The displacement at load a (its weighted mean) per unit force spread as load b: 3 x 3 (m/N).
/// The fixed region's nodes neither move nor take load.
Eigen::Matrix3d ContactLoadCompliance(const BemModel& model, const BemContactLoad& a, const BemContactLoad& b);

/// du (3#V, the reference unknowns' layout of BemModel::greens) += the response to `force_N`
/// spread as `load`.
void AddContactLoadResponse(const BemModel& model, const BemContactLoad& load, const Eigen::Vector3d& force_N,
                            Eigen::VectorXd& du);

}  // namespace vesica::physics
