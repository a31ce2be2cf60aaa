#pragma once
// Named errors of the BEM body. Mesh defects are reported as MeshError (mesh_validation.h).

#include <stdexcept>

namespace vesica::physics {

/// Input the BEM cannot use (material, boundary conditions, node indices); what() names it.
class BemError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A reference problem or contact set whose system matrix is singular (e.g. no fixed region,
/// a node listed twice); raised instead of returning garbage displacements.
class SingularSystemError : public BemError {
 public:
  using BemError::BemError;
};

}  // namespace vesica::physics
