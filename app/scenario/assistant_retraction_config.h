#pragma once
// The assistant's fixed retraction of the gallbladder's fundus (scenario [assistant_retraction]):
// the fundus's nodes near the grasp point held by stiff springs to targets displaced cranially
// over the liver's edge. The physics side is physics/scene/assistant_retraction.h.

#include <Eigen/Core>

#include "physics/scene/assistant_retraction.h"

namespace vesica::app {

struct AssistantRetractionConfig {
  Eigen::Vector3d grasp_point_m = Eigen::Vector3d::Zero();   ///< on the fundus, patient frame
  double radius_m = 0.01;                                    ///< nodes within this are held
  Eigen::Vector3d displacement_m = Eigen::Vector3d::Zero();  ///< targets = rest + this
  double stiffness_N_per_m = 50.0;                           ///< per held node
  double damping_Ns_per_m = 0.05;                            ///< per held node
};

inline physics::AssistantRetractionSettings ToPhysics(const AssistantRetractionConfig& c) {
  return {true, c.grasp_point_m, c.radius_m, c.displacement_m, c.stiffness_N_per_m, c.damping_Ns_per_m};
}

}  // namespace vesica::app
