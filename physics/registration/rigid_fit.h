#pragma once
// The rigid-only baseline the registration is compared with: point-to-plane ICP of the rest
// surface to the control points (Chen and Medioni's linearised step, re-paired with the same
// normal-checked pairing every iteration). It shows what no rigid motion can capture.

#include <Eigen/Geometry>
#include <vector>

#include "physics/mesh/mesh_types.h"
#include "physics/registration/control_point.h"
#include "physics/registration/surface_pairing.h"

namespace vesica::physics {

struct RigidFitOptions {
  PairingOptions pairing;
  int iterations = 30;
};

/// x = R X + t minimising sum_i (n_i . (x_s,i - q_i))^2, started from `initial` (the previous
/// frame's fit). `rest_W`: the rest positions (#V by 3).
Eigen::Isometry3d FitRigid(const RegistrationSurface& surface, const Vertices& rest_W,
                           const std::vector<ControlPoint>& points, const Eigen::Isometry3d& initial,
                           const RigidFitOptions& options = {});

/// The rest positions moved by a rigid transform.
Vertices TransformVertices(const Vertices& rest_W, const Eigen::Isometry3d& transform);

}  // namespace vesica::physics
