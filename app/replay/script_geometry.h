#pragma once
// Geometry the scripted surgeons share (scripted_surgeon.cpp, calot_scripted_surgeon.cpp): a
// tool tip moved at a bounded speed, the pose that puts a tip at a point, outward vertex normals.

#include <Eigen/Core>

#include "physics/instrument/instrument_pose.h"
#include "physics/mesh/triangle_mesh.h"
#include "physics/scene/dissection_settings.h"

namespace vesica::app {

/// `from` moved toward `to` by at most max_step (m).
Eigen::Vector3d MoveToward(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double max_step);

/// The instrument's pose with its tip at `tip` (through the mount's remote centre) and the jaws at
/// jaw_rad.
physics::InstrumentPose PoseFor(const physics::InstrumentMount& mount, const Eigen::Vector3d& tip, double jaw_rad);

/// Outward vertex normals of a closed surface at positions x (area-weighted, unit).
physics::Vertices VertexNormals(const physics::TriangleMesh& surface, const physics::Vertices& x);

}  // namespace vesica::app
