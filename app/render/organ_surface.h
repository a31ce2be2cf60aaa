#pragma once
// A deforming organ surface in VTK (internal to app/render): moves with the physics' vertices,
// relit with recomputed normals, mottled tissue colour burnt by the physics' burn map.
//
// The physics burns per triangle; drawn so, a burn on the 1,000-vertex liver shows as facets.
// Each vertex therefore takes the highest burn of the triangles around it and the colour is
// interpolated across each triangle: the burnt triangles keep their colour, and the burn fades
// to the tissue over the ring of triangles around them, with no step at an edge.
// The triangles are drawn unshared (3 points per triangle, a "soup") so that the texture can be
// box-mapped per triangle; the liver has 2k triangles: 6k points.
// A texture, when given, is box-mapped from the rest shape (each triangle projected along the
// axis its rest normal is closest to; the soup makes that seam-free per triangle), so the
// texture sticks to the tissue as it deforms.

#include <vtkSmartPointer.h>

#include <vector>

#include "app/render/display_bounds.h"
#include "physics/mesh/triangle_mesh.h"

class vtkActor;
class vtkPolyData;
class vtkTexture;

namespace vesica::app {

class OrganSurface {
 public:
  /// @param rest  the surface at rest (its numbering is the frame's)
  /// @param rgb   tissue colour 0..1; @param mottle_amplitude relative shade variation
  /// @param texture multiplies the colour (null: none); @param texture_tile_m its period on the tissue
  OrganSurface(const physics::TriangleMesh& rest, const double rgb[3], double mottle_amplitude, double opacity,
               vtkTexture* texture = nullptr, double texture_tile_m = 0.03);
  vtkActor* actor() const;
  /// What the mapper draws: 3 points per triangle, normals, colours and (if textured) TCoords.
  vtkPolyData* poly_data() const;
  int num_vertices() const { return rest_.num_vertices(); }
  int num_triangles() const { return rest_.num_triangles(); }

  /// #V by 3 current positions, or empty for the rest shape. Sizes are checked by the caller.
  void SetVertices(const physics::Vertices& vertices);
  /// #F burn levels, or empty for unburned.
  void SetBurn(const std::vector<float>& burn);
  /// The burn each vertex is drawn with (#V): the highest burn of its triangles.
  const std::vector<float>& vertex_burn() const { return burn_; }
  /// The box of the points drawn now (display frame): what VTK's bounds of the actor would be.
  const DisplayBounds& bounds_D() const { return bounds_D_; }

  /// Physically based shading (VTK's PBR) instead of Phong: `roughness` 0 (mirror) .. 1 (matte);
  /// the colour texture given at construction becomes the base-colour texture, and `normal_map`
  /// (tangent space, may be null) adds relief with strength `normal_scale`.
  void UsePbr(double roughness, vtkTexture* normal_map, double normal_scale);

 private:
  void WriteGeometry(const physics::Vertices& vertices);

  physics::TriangleMesh rest_;
  double rgb_[3];
  std::vector<double> shade_;     // per vertex, from the rest position (mottle sticks to tissue)
  std::vector<float> burn_;       // per vertex: what the colours show now
  std::vector<float> next_burn_;  // per vertex, scratch for SetBurn
  vtkTexture* texture_ = nullptr;
  bool deformed_ = false;
  DisplayBounds bounds_D_;
  vtkSmartPointer<vtkPolyData> poly_;
  vtkSmartPointer<vtkActor> actor_;
};

}  // namespace vesica::app
