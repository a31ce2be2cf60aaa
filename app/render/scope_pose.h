#pragma once
// Where the laparoscope's camera is and how it is held (patient frame). No VTK.

#include <Eigen/Core>

#include "app/scenario/scenario.h"

namespace vesica::app {

struct ScopePose {
  Eigen::Vector3d eye_W;      ///< the scope's tip: camera and light source
  Eigen::Vector3d forward_W;  ///< unit line of sight, tip to look_at
  Eigen::Vector3d up_W;       ///< unit image "up", orthogonal to forward_W
};

/// The tip sits insertion_m in from the port along the line to look_at (the 30-degree optic looks
/// along that line; its shaft is tilted, which the picture does not show). The camera assistant
/// keeps the horizon: the anterior abdominal wall (+y) at the top of the image, or cranial (+z)
/// when the scope looks straight up or down the y axis.
ScopePose ScopePoseOf(const LaparoscopeConfig& scope);

}  // namespace vesica::app
