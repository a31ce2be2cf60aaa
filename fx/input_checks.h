#pragma once
// Checks of caller input at fx's door: each throws std::invalid_argument naming the owner
// (e.g. "BurnMap 'liver'"), the field and the offending value.

#include <Eigen/Core>
#include <string>

namespace vesica::fx {

/// Throws unless 0 <= index < size.
void CheckIndex(const std::string& owner, const char* field, int index, int size);
/// Throws unless value is finite and >= 0.
void CheckNonNegative(const std::string& owner, const char* field, double value);
/// Throws unless value is finite and > 0.
void CheckPositive(const std::string& owner, const char* field, double value);
/// Throws unless every component is finite.
void CheckFinite(const std::string& owner, const char* field, const Eigen::Vector3d& v);

}  // namespace vesica::fx
