#pragma once
// The error every FEM entry point throws for bad input; what() names the body and, where there is
// one, the element or node, e.g. "gallbladder: tetrahedron 17: inverted".

#include <stdexcept>

namespace vesica::physics {

class FemError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vesica::physics
