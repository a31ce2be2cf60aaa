#pragma once
// The surgeon's feedback in the field of view (internal to app/render): small labels in the
// picture's lower corners, under each hand's instrument, as a laparoscopy tower shows the
// generator's state: the grasper's grasp (holding, slipped, empty) on the left, the hook's pedal
// (CUT while pressed) on the right, and each haptic arm's link at the bottom centre. Drawn over
// the scene, unlit, in muted colours until something needs attention.

#include <string>
#include <vector>

#include <vtkSmartPointer.h>

#include "app/render/render_frame.h"

class vtkTextActor;
class vtkRenderer;

namespace vesica::app {

class FieldStatusOverlay {
 public:
  /// Adds its labels to `renderer`. `grasper` and `hook` index RenderFrame::instruments (-1: absent).
  FieldStatusOverlay(vtkRenderer* renderer, int grasper, int hook);

  void Update(const RenderFrame& frame);

  /// What the labels say now (tests read them; the picture shows them).
  std::string grasp_text() const;
  std::string pedal_text() const;
  std::string arm_text() const;

 private:
  vtkRenderer* renderer_;
  int grasper_, hook_;
  vtkSmartPointer<vtkTextActor> grasp_, pedal_, arms_;
};

}  // namespace vesica::app
