#pragma once
// The reference boundary-value problem of the capacitance matrix algorithm (paper Fig. 1a): zero
// displacement on the fixed region (vertices labelled kLabelFixed), prescribed traction (zero by
// default) on the free surface. Its unknowns Y0 are the free nodes' displacements and the fixed
// nodes' tractions, in node order: A0 Y0 = G_free t_free with A0 = [H_free | -G_fixed].

#include <Eigen/Core>
#include <string>
#include <vector>

#include "physics/bem/bem_matrices.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

struct BemNodeLayout {
  std::vector<int> fixed_nodes;  ///< vertices with kLabelFixed, ascending
  std::vector<int> free_nodes;   ///< all others, ascending
  Eigen::VectorXi free_index;    ///< #V: position in free_nodes, -1 for fixed vertices
};

/// Reads the fixed region from surface.vertex_labels. Throws BemError (naming `source`) when the
/// labels are missing or the region cannot hold the body: fewer than 3 non-collinear vertices
/// leave a rigid rotation free and the reference problem singular.
BemNodeLayout MakeBemNodeLayout(const TriangleMesh& surface, const std::string& source);

/// Green's functions Xi = A0^{-1} G_free (3#V x 3#free): column 3f+k is the response of every
/// reference unknown to a unit traction component k at free node f. Consumes the matrices
/// (A0 is built in H's storage). Throws SingularSystemError when A0 is singular.
Eigen::MatrixXd ComputeGreensFunctions(BemMatrices&& matrices, const BemNodeLayout& layout);

}  // namespace vesica::physics
