#pragma once
// One instrument in VTK (internal to app/render): a steel shaft through its trocar and its tip,
// two jaws opening with the jaw angle (grasper) or an L-shaped hook (cautery). The jaws turn
// amber-red while a grasp slips; the hook glows while the cautery cuts.

#include <vector>

#include <Eigen/Core>
#include <vtkSmartPointer.h>

#include "app/render/render_frame.h"
#include "app/scenario/scenario.h"

class vtkActor;
class vtkLineSource;
class vtkSphereSource;

namespace vesica::app {

class InstrumentActors {
 public:
  /// `reference_direction`: the shaft direction at yaw = pitch = 0 (unit).
  InstrumentActors(const InstrumentConfig& config, const Eigen::Vector3d& remote_centre,
                   const Eigen::Vector3d& reference_direction);
  const std::vector<vtkSmartPointer<vtkActor>>& actors() const { return actors_; }
  const Eigen::Vector3d& remote_centre() const { return remote_centre_; }
  const Eigen::Vector3d& reference_direction() const { return reference_direction_; }

  void Update(const InstrumentFrame& frame);

 private:
  InstrumentConfig config_;
  Eigen::Vector3d remote_centre_;
  Eigen::Vector3d reference_direction_;
  vtkSmartPointer<vtkLineSource> shaft_line_, tip_a_, tip_b_;
  vtkSmartPointer<vtkSphereSource> glow_;
  vtkSmartPointer<vtkActor> shaft_, jaw_a_, jaw_b_, glow_actor_;
  std::vector<vtkSmartPointer<vtkActor>> actors_;
};

}  // namespace vesica::app
