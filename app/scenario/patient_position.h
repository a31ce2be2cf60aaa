#pragma once
// The patient's position on the table (scenario [patient]): reverse Trendelenburg and a tilt to
// the left let the bowel fall away from the gallbladder; here they set the direction of gravity
// on the simulated gallbladder, in the patient frame (x left, y anterior, z cranial).

#include <Eigen/Core>

namespace vesica::app {

struct PatientPosition {
  bool given = false;                    ///< false: no [patient] table, no gravity (the default scene)
  double reverse_trendelenburg_deg = 0;  ///< head up (negative: Trendelenburg, head down)
  double left_tilt_deg = 0;              ///< the patient's left side down (negative: right side down)
  double gravity_m_per_s2 = 9.81;        ///< magnitude
};

/// Gravity in the patient frame: (0, -g, 0) on a level table; reverse Trendelenburg a and left
/// tilt b give g (sin b cos a, -cos b cos a, -sin a). Zero when !given.
Eigen::Vector3d GravityInPatientFrame(const PatientPosition& patient);

}  // namespace vesica::app
