#pragma once
// Assembled small-strain stiffness matrices of three tet formulations (issue 37's gallbladder
// study: which element gets a grasper's force within 10 % on the trainer's 1,000-node mesh):
//
//   linear       the trainer's 4-node tet (constant strain), one point: the matrix FemModel has.
//   nodal        the average-nodal-pressure 4-node tet (Bonet & Burton 1998, Comm. Numer. Meth.
//   pressure     Eng. 14; Dohrmann et al. 2000 for the nodal averaging): the deviatoric energy per
//                element as above, the volumetric energy per node, kappa/2 V_a theta_a^2 with the
//                node's volumetric strain theta_a the volume-weighted mean of its elements'
//                (V_a = sum V_e / 4). A constant volumetric strain is kept exactly (patch test);
//                the incompressibility constraint is counted once per node instead of once per
//                tet, which removes the linear tet's volumetric locking (nu = 0.45: kappa = 9.7 mu).
//                Couples nodes two elements apart (a denser matrix).
//   quadratic    10-node tets on the same mesh (quadratic_tet_mesh.h), straight edges; the
//                4-point Gauss rule, exact for B^T D B on a straight tet.
//
// Each returns the symmetric 3n x 3n matrix (N/m, node-major dofs x0 y0 z0 x1 ...), full storage.

#include <Eigen/SparseCore>

#include "physics/fem/elastic_material.h"
#include "physics/fem/quadratic_tet_mesh.h"
#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

/// Throws std::invalid_argument naming the tet when one is inverted or flat (volume <= 0).
Eigen::SparseMatrix<double> LinearTetStiffness(const TetrahedralMesh& mesh, const ElasticMaterial& material);
Eigen::SparseMatrix<double> NodalPressureTetStiffness(const TetrahedralMesh& mesh, const ElasticMaterial& material);
Eigen::SparseMatrix<double> QuadraticTetStiffness(const QuadraticTetMesh& mesh, const ElasticMaterial& material);

}  // namespace vesica::physics
