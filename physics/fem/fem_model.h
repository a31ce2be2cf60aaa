#pragma once
// The const part of a FEM body (STYLE.md item 2): rest mesh, element data, mass, linear stiffness,
// sparsity and Dirichlet set. Built once; FemBody keeps the per-step state apart.

#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "physics/fem/element_batches.h"
#include "physics/fem/fem_settings.h"
#include "physics/fem/sparse_pattern.h"
#include "physics/fem/tangent_blocks.h"
#include "physics/fem/tet_element.h"
#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

/// A node held fixed (zero displacement increment) along the flagged world axes.
struct DirichletNode {
  int node = -1;
  std::array<bool, 3> axes = {true, true, true};
};

struct FemModel {
  FemSettings settings;
  TetrahedralMesh rest_mesh;         ///< metres
  std::vector<TetElement> elements;  ///< one per tet
  ElementBatches element_batches;    ///< the same, in SIMD blocks
  double lame_lambda_Pa = 0.0;
  double lame_mu_Pa = 0.0;
  SparsePattern pattern;
  /// The pattern's blocks with their tets, for the SIMD pass's corotational tangent.
  TangentBlocks tangent_blocks;
  /// Lumped mass per dof (3n, kg); always filled (gravity, kinetic energy with lumped mass).
  Eigen::VectorXd lumped_mass_kg;
  /// Consistent mass values in pattern order (nnz, kg); empty with MassModel::kLumped.
  Eigen::VectorXd consistent_mass_values;
  /// Linear stiffness values in pattern order (nnz, N/m), no Dirichlet rows removed.
  Eigen::VectorXd linear_stiffness_values;
  /// 1 for a free dof, 0 for a fixed one (3n).
  Eigen::VectorXd free_dofs;
  std::vector<int> fixed_dofs;
  /// Value indices whose row or column is a fixed dof (zeroed in system matrices).
  std::vector<int> constrained_slots;

  int num_nodes() const { return rest_mesh.num_vertices(); }
  int num_dofs() const { return 3 * rest_mesh.num_vertices(); }
  bool uses_consistent_mass() const { return consistent_mass_values.size() > 0; }
  /// y = M x with the model's mass (lumped or consistent).
  Eigen::VectorXd MassTimes(const Eigen::VectorXd& x) const;
  /// x . M x (twice a kinetic energy); no temporary vector with the lumped mass.
  double MassQuadraticForm(const Eigen::VectorXd& x) const;
  /// Nodal gravity forces M g (N), g in m/s^2.
  Eigen::VectorXd GravityForces(const Eigen::Vector3d& g_m_per_s2) const;
};

/// Validates settings, material and mesh (errors name settings.body_name and the tet or node),
/// then precomputes everything. Throws FemError (or MeshError for mesh defects).
FemModel BuildFemModel(const TetrahedralMesh& mesh, const FemSettings& settings,
                       const std::vector<DirichletNode>& fixed_nodes);

/// Matrix view sharing the pattern's structure with the given value array (nnz entries).
Eigen::Map<const Eigen::SparseMatrix<double>> PatternMatrix(const SparsePattern& pattern,
                                                            const Eigen::VectorXd& values);

}  // namespace vesica::physics
