#pragma once
// Cautery smoke as camera-facing, alpha-blended soft discs (internal to app/render), one per
// particle, greyish white, each with its own size and opacity (vtkPointGaussianMapper).

#include <vector>

#include <vtkSmartPointer.h>

#include "app/render/render_frame.h"

class vtkActor;
class vtkPolyData;

namespace vesica::app {

class SmokeSprites {
 public:
  SmokeSprites();
  vtkActor* actor() const { return actor_; }
  /// Values are checked by the caller; alpha is clamped to [0,1]. Hidden when there is no smoke.
  void Update(const std::vector<SmokeSprite>& smoke);

 private:
  vtkSmartPointer<vtkPolyData> poly_;
  vtkSmartPointer<vtkActor> actor_;
};

}  // namespace vesica::app
