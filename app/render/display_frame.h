#pragma once
// The frame the view draws in. The patient frame (x left, y anterior, z cranial) is
// left-handed; VTK and OpenGL are right-handed. Drawn as given, every picture would be the
// mirror image of the patient: the liver's right lobe on the right of the screen, as no
// laparoscope shows it. The view therefore mirrors x at its input (points, normals, the
// camera) and reverses each triangle's winding, so that faces stay front-facing and lit. A
// transform on the camera or the actors cannot do it: VTK flips the normals of faces whose
// screen winding turned, and everything goes black.

#include <Eigen/Core>

namespace vesica::app {

/// A point or direction of the patient frame in the display frame (x negated).
inline Eigen::Vector3d ToDisplay(const Eigen::Vector3d& v_W) { return {-v_W.x(), v_W.y(), v_W.z()}; }

}  // namespace vesica::app
