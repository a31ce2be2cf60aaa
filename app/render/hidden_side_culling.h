#pragma once
// Culling the side of a closed surface that faces away from the camera (internal to app/render).
// A closed organ seen from outside hides its far side behind its near side; drawn anyway, the far
// side cost llvmpipe's triangle setup on the main thread about as much as the near side (the
// context organs are most of the scene's triangles). The back faces are culled when the surface
// is wound outward, the front faces when inward, nothing when it is not closed (closed: its
// signed volume does not change with the reference point). A camera put inside such a surface
// would no longer see its inner wall.

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>

#include <Eigen/Geometry>
#include <cmath>

namespace vesica::app {

/// `surface`: what `actor` draws (polygons; a surface with strips is left alone).
inline void CullHiddenSide(vtkActor* actor, vtkPolyData* surface) {
  if (surface->GetNumberOfStrips() > 0) return;  // only polygons are summed below
  const double* b = surface->GetBounds();
  const Eigen::Vector3d shift(b[1] - b[0] + 1.0, b[3] - b[2] + 1.0, b[5] - b[4] + 1.0);
  double volume = 0, volume_shifted = 0, magnitude = 0;
  vtkCellArray* polys = surface->GetPolys();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  Eigen::Vector3d p[3];
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    for (vtkIdType k = 1; k + 1 < n; ++k) {  // a fan over each polygon
      surface->GetPoint(ids[0], p[0].data());
      surface->GetPoint(ids[k], p[1].data());
      surface->GetPoint(ids[k + 1], p[2].data());
      const double tetra = p[0].dot(p[1].cross(p[2])) / 6.0;
      volume += tetra;
      magnitude += std::abs(tetra);
      volume_shifted += (p[0] - shift).dot((p[1] - shift).cross(p[2] - shift)) / 6.0;
    }
  if (magnitude == 0 || std::abs(volume_shifted - volume) > 1e-6 * magnitude) return;  // open
  if (volume > 0)
    actor->GetProperty()->BackfaceCullingOn();
  else
    actor->GetProperty()->FrontfaceCullingOn();
}

}  // namespace vesica::app
