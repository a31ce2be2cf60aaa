#pragma once
// The connective-tissue membrane between gallbladder and liver bed (internal to app/render): a
// thin translucent whitish-yellow sheet, each triangle as opaque as the physics says (0 = cut
// away, not drawn at all), darker where burned.

#include <vector>

#include <vtkSmartPointer.h>

#include "physics/mesh/mesh_types.h"

class vtkActor;
class vtkPolyData;

namespace vesica::app {

class MembraneSheet {
 public:
  MembraneSheet();
  vtkActor* actor() const { return actor_; }

  /// Sizes and indices are checked by the caller (ValidateRenderFrame). Empty opacity = all 1,
  /// empty burn = unburned. Hides the actor when no triangle is left to draw.
  void Update(const physics::Vertices& vertices, const physics::Triangles& triangles,
              const std::vector<float>& opacity, const std::vector<float>& burn);

 private:
  vtkSmartPointer<vtkPolyData> poly_;
  vtkSmartPointer<vtkActor> actor_;
};

}  // namespace vesica::app
