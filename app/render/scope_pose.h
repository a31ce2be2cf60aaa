#pragma once
// Where the laparoscope's camera is and how it is held (patient frame). No VTK.

#include <Eigen/Core>

#include "app/scenario/scenario.h"

namespace vesica::app {

struct ScopePose {
  Eigen::Vector3d eye_W;      ///< the scope's tip: camera and light source
  Eigen::Vector3d forward_W;  ///< unit line of sight, tip to look_at
  Eigen::Vector3d up_W;       ///< unit image "up", orthogonal to forward_W
  Eigen::Vector3d shaft_W;    ///< unit direction of the scope's shaft, port to tip
};

/// An angled laparoscope held as the camera assistant holds a 30-degree scope for a
/// cholecystectomy. The tip sits on the shaft, insertion_m in from the port; the optic looks
/// scope_angle_deg off the shaft, its light post turned so that the view looks down onto the
/// field: the shaft is tilted toward the anterior wall from the port->look_at line and the line
/// of sight comes down from the tip onto look_at, which stays the centre of the image. With a
/// 0-degree scope the shaft is that line (a negative angle turns the light post the other way:
/// the shaft below the line, looking up). The horizon is kept: the anterior abdominal wall (+y)
/// at the top of the image, or cranial (+z) when the scope looks straight up or down the y axis.
/// Throws std::invalid_argument when look_at is not beyond the tip (insertion_m >= the port's
/// distance to look_at) or the angle is outside (-90, 90) degrees.
ScopePose ScopePoseOf(const LaparoscopeConfig& scope);

}  // namespace vesica::app
