#pragma once
// The connective-tissue membrane between gallbladder and liver bed (internal to app/render): a
// thin translucent whitish-yellow sheet, each triangle as opaque as the physics says (0 = cut
// away, not drawn at all), darker where burned. Drawn with plain alpha blending (no depth
// peeling, which cost the main thread half its frame under llvmpipe): its triangles are kept in
// back-to-front order from the eye (SortBackToFront), so where the sheet overlaps itself it
// composites as depth peeling did.

#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "app/render/display_bounds.h"
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
  void Update(const physics::Vertices& vertices, const physics::Triangles& triangles, const std::vector<float>& opacity,
              const std::vector<float>& burn);

  /// Orders the drawn triangles farthest first from `eye_D` (display frame), by centroid; call
  /// before each render (the camera may have moved since Update).
  void SortBackToFront(const Eigen::Vector3d& eye_D);

  /// The box of the triangles drawn (display frame; empty when none is).
  const DisplayBounds& bounds_D() const { return bounds_D_; }

 private:
  void WriteCells();

  // The drawn triangles (display-frame winding) and their colours, in drawing order.
  std::vector<std::array<vtkIdType, 3>> cells_;
  std::vector<std::array<unsigned char, 4>> rgba_;
  std::vector<Eigen::Vector3d> centroids_D_;
  std::vector<std::size_t> order_, scratch_order_;
  DisplayBounds bounds_D_;
  vtkSmartPointer<vtkPolyData> poly_;
  vtkSmartPointer<vtkActor> actor_;
};

}  // namespace vesica::app
