#include "fx/input_checks.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace vesica::fx {

void CheckIndex(const std::string& owner, const char* field, int index, int size) {
  if (index < 0 || index >= size) {
    std::ostringstream msg;
    msg << owner << ": " << field << " " << index << " out of range [0, " << size << ")";
    throw std::invalid_argument(msg.str());
  }
}

void CheckNonNegative(const std::string& owner, const char* field, double value) {
  if (!std::isfinite(value) || value < 0) {
    std::ostringstream msg;
    msg << owner << ": " << field << " must be finite and >= 0, got " << value;
    throw std::invalid_argument(msg.str());
  }
}

void CheckPositive(const std::string& owner, const char* field, double value) {
  if (!std::isfinite(value) || value <= 0) {
    std::ostringstream msg;
    msg << owner << ": " << field << " must be finite and > 0, got " << value;
    throw std::invalid_argument(msg.str());
  }
}

void CheckFinite(const std::string& owner, const char* field, const Eigen::Vector3d& v) {
  if (!v.allFinite()) {
    std::ostringstream msg;
    msg << owner << ": " << field << " is not finite (" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace vesica::fx
