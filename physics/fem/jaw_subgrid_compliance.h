#pragma once
// The give a grasper's jaw finds in the tissue under it that the trainer's linear tets cannot
// resolve (issue 37), to be added in series to the jaw's constraint rows.
//
// Under a 10 x 5 mm jaw on the gallbladder's 3.6 mm edges the linear tets are 28 % too stiff
// (docs/fidelity.md): the traction is singular at the jaw's edges and the constant-strain tets
// lock in bending there. The error sits in the few elements under and around the jaw, so it is
// corrected there: on the patch of tets within patch_radius_m of the jaw's centre, its cut faces
// held, the jaw's 3 x 3 compliance is computed twice,
//   - with the trainer's linear tets and the jaw as its footprint's mean (the rows the scene
//     builds), and
//   - with 10-node tets on the same mesh and the jaw as a grid of 4 x 2 cells each moving with it
//     (on the whole body within 1.1-1.4 % of the converged continuum's rigid jaw),
// and their difference is the subgrid compliance: a spring in series with the body's own rows,
// so the jaw feels the continuum's stiffness while the body keeps its linear tets and its step.
// Both patches hold the same cut, whose effect cancels in the difference (the patch radius's
// convergence is tested). A press (closed jaws pushed on the wall, frictionless) holds only the
// normal component: its compliance is the normal one with the tangential components free.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "physics/fem/elastic_material.h"
#include "physics/fem/jaw_footprint.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

struct JawSubgridSettings {
  double patch_radius_m = 0.015;  ///< tets with a corner this near the jaw's centre, > 0
  int cells_along = 4;            ///< the continuum jaw's grid of cells, >= 1 each
  int cells_across = 2;
};

struct JawSubgridCompliance {
  /// On the body's own mesh, in its node numbers: the jaw's rows move sum_i w_i u_i (weights
  /// summing to 1, the footprint's mean).
  std::vector<int> nodes;
  std::vector<double> weights;
  /// Pull (every component held), m/N, symmetric: the linear patch's, the 10-node patch's, and
  /// their difference with its negative eigenvalues set to zero (a spring cannot add stiffness).
  Eigen::Matrix3d linear_m_per_N = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d quadratic_m_per_N = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d subgrid_m_per_N = Eigen::Matrix3d::Zero();
  /// Press along -normal (the tangential components free), m/N; subgrid >= 0.
  double linear_normal_m_per_N = 0;
  double quadratic_normal_m_per_N = 0;
  double subgrid_normal_m_per_N = 0;
  int patch_tets = 0;
  int patch_dofs = 0;  ///< free dofs of the 10-node patch
};

/// W = C K^-1 C^T (m x m, symmetric): the displacements the rows C (m x 3n) see under unit row
/// forces, K (3n x 3n, symmetric) with the held dofs (3n flags) fixed at zero; one CHOLMOD
/// factorisation. Throws FemError when K on the free dofs is not positive definite.
Eigen::MatrixXd HeldRowCompliance(const Eigen::SparseMatrix<double>& k, const std::vector<bool>& held_dof,
                                  const Eigen::MatrixXd& rows);

/// The jaw on a body at rest: `mesh` its rest mesh, `boundary` = ExtractBoundary(mesh), the jaw's
/// rectangle on that rest surface. Throws std::invalid_argument naming the field for bad settings
/// or jaw (jaw_footprint.h's checks, and "no surface under the jaw"), FemError when the patch is
/// not held (it is the whole body: no cut faces) or a tet is inverted.
JawSubgridCompliance ComputeJawSubgridCompliance(const TetrahedralMesh& mesh, const TetBoundary& boundary,
                                                 const ElasticMaterial& material, const RectangularFootprint& jaw,
                                                 const JawSubgridSettings& settings = {});

}  // namespace vesica::physics
