#pragma once
// Calot's triangle drawn (internal to app/render): the ducts and the artery as tubes coloured as
// a surgeon sees them (bile ducts grey-green, the artery red), titanium clips across them, the
// fat-and-fibrous layer as one smooth yellow surface over its intact cells that hides what it
// covers and opens where cells are burnt or torn away (CalotFatSurface), and a pool of blood or
// bile at an open end. Rebuilt from each frame's CalotDrawing: cuts change the pieces.

#include <vtkSmartPointer.h>

#include <vector>

#include "app/render/calot_drawing.h"
#include "app/render/calot_fat_surface.h"

class vtkActor;
class vtkPolyData;

namespace vesica::app {

class CalotActors {
 public:
  explicit CalotActors(bool pbr = false);
  ~CalotActors();
  CalotActors(const CalotActors&) = delete;
  CalotActors& operator=(const CalotActors&) = delete;

  /// The actors to add to the renderer (tubes, clips, fat, leaks).
  std::vector<vtkActor*> actors() const;
  void Update(const CalotDrawing& drawing);

  /// The fat layer's surface (its rebuild count tells tests when the set of cells changed).
  const CalotFatSurface& fat() const { return fat_; }

 private:
  vtkSmartPointer<vtkPolyData> tube_lines_, clip_points_, leak_points_;
  CalotFatSurface fat_;
  std::vector<vtkSmartPointer<vtkActor>> actors_;
};

/// Colours before lighting (0..1): bile ducts grey-green, the artery red.
Eigen::Vector3d CalotTubeColour(physics::calot::TubeKind kind);

}  // namespace vesica::app
