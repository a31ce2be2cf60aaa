#pragma once
// One jaw of an atraumatic fenestrated grasper (internal to app/render): a flat, rounded blade
// with a long window through it, as on a Johann or DeBakey laparoscopic grasper. Built once in
// the jaw's own frame and placed each frame by the instrument's pose.

#include <vtkSmartPointer.h>

class vtkPolyData;

namespace vesica::app {

/// Jaw dimensions (m). The window is centred on the blade.
struct GrasperJawShape {
  double length_m = 0.018;         ///< hinge to tip, along x
  double width_m = 0.0045;         ///< across the blade, along z
  double thickness_m = 0.0018;     ///< from the grasping face (y = 0) to the back (y = thickness)
  double window_length_m = 0.011;  ///< the fenestration, along x
  double window_width_m = 0.0022;  ///< the fenestration, along z
};

/// The jaw as a closed, outward-facing triangle surface with normals: x from the hinge (0) to the
/// tip, the grasping face at y = 0, the back at y = thickness_m, z across. Throws
/// std::invalid_argument when the window does not fit inside the blade.
vtkSmartPointer<vtkPolyData> MakeGrasperJaw(const GrasperJawShape& shape);

/// Whether (x, z) of the jaw's face lies inside the window (the test's independent outline).
bool InGrasperJawWindow(const GrasperJawShape& shape, double x_m, double z_m);
/// Whether (x, z) lies on the blade's outline (the blade minus nothing: window included).
bool InGrasperJawOutline(const GrasperJawShape& shape, double x_m, double z_m);

}  // namespace vesica::app
