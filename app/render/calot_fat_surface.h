#pragma once
// The fat-and-fibrous layer of Calot's triangle as one smooth surface (internal to app/render):
// the intact cells of the physics' fat layer (physics/calot/fat_layer.h) each spread a smooth
// bump of density; the surface is where the summed density reaches a level, so neighbouring
// cells merge into a continuous layer and removed cells leave holes. Built at the cells' rest
// places (a lattice) only when the set of intact cells changes; each frame its vertices move by
// the cells' displacements, weighted as the density is.

#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <vector>

class vtkPolyData;

namespace vesica::app {

class CalotFatSurface {
 public:
  CalotFatSurface();
  ~CalotFatSurface();
  CalotFatSurface(const CalotFatSurface&) = delete;
  CalotFatSurface& operator=(const CalotFatSurface&) = delete;

  /// The intact cells in the display frame: rest_D at their lattice places (spacing cell_m),
  /// now_D where they are, in the same order (same size). Rebuilds the surface when rest_D is
  /// not the last call's, else only moves it. Throws std::invalid_argument when the sizes differ
  /// or cell_m is not > 0.
  void Update(const std::vector<Eigen::Vector3d>& rest_D, const std::vector<Eigen::Vector3d>& now_D, double cell_m);

  /// Triangles with point normals, display frame; empty without cells.
  vtkPolyData* surface() const;
  /// How many times the surface was rebuilt (a changed set of intact cells).
  int rebuilds() const { return rebuilds_; }

 private:
  void Rebuild(const std::vector<Eigen::Vector3d>& rest_D, double cell_m);
  void Move(const std::vector<Eigen::Vector3d>& rest_D, const std::vector<Eigen::Vector3d>& now_D);

  vtkSmartPointer<vtkPolyData> surface_;
  std::vector<Eigen::Vector3d> rest_D_, now_D_;  // the last call's cells
  double cell_m_ = 0.0;
  // The vertices at rest and, per vertex, the cells that carry it: weights_[offsets_[v] ..
  // offsets_[v + 1]) of cells_[...], summing to 1 (none: the vertex stays).
  std::vector<Eigen::Vector3d> vertices_rest_D_;
  std::vector<int> offsets_, cells_;
  std::vector<double> weights_;
  int rebuilds_ = 0;
};

}  // namespace vesica::app
