#include "app/scenario/patient_position.h"

#include <cmath>
#include <numbers>

namespace vesica::app {

Eigen::Vector3d GravityInPatientFrame(const PatientPosition& p) {
  if (!p.given) return Eigen::Vector3d::Zero();
  const double a = p.reverse_trendelenburg_deg * std::numbers::pi / 180.0;
  const double b = p.left_tilt_deg * std::numbers::pi / 180.0;
  return p.gravity_m_per_s2 * Eigen::Vector3d(std::sin(b) * std::cos(a), -std::cos(b) * std::cos(a), -std::sin(a));
}

}  // namespace vesica::app
