#include "app/render/instrument_actors.h"

#include <vtkActor.h>
#include <vtkLineSource.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkTubeFilter.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "app/render/display_frame.h"
#include "app/render/render_colours.h"

namespace vesica::app {

namespace {

// Laparoscopic instruments: a black insulated shaft (the electrode's insulation, the grasper's
// too), bare steel only at the working end.
constexpr double kInsulationGrey = 0.06;
constexpr double kJawGrey = 0.45;
constexpr double kJawLength_m = 0.018;
constexpr double kHookStem_m = 0.012;
constexpr double kHookFoot_m = 0.006;

vtkSmartPointer<vtkActor> Tube(vtkLineSource* line, double radius) {
  auto tube = vtkSmartPointer<vtkTubeFilter>::New();
  tube->SetInputConnection(line->GetOutputPort());
  tube->SetRadius(radius);
  tube->SetNumberOfSides(16);
  tube->CappingOn();
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(tube->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.8);
  actor->GetProperty()->SetSpecularPower(60);
  return actor;
}

void Steel(vtkActor* actor, double grey) {
  auto* p = actor->GetProperty();
  p->SetColor(grey, grey, grey * 1.03);
  p->SetAmbient(0.0);
  p->SetDiffuse(1.0);
  p->SetSpecular(0.8);
}

// Lit from inside: full ambient so it reads as light, not as a painted surface.
void Emissive(vtkActor* actor, const double rgb[3]) {
  auto* p = actor->GetProperty();
  p->SetColor(rgb[0], rgb[1], rgb[2]);
  p->SetAmbient(1.0);
  p->SetDiffuse(0.3);
  p->SetSpecular(0.0);
}

}  // namespace

InstrumentActors::InstrumentActors(const InstrumentConfig& config, const Eigen::Vector3d& remote_centre,
                                   const Eigen::Vector3d& reference_direction)
    : config_(config), remote_centre_(remote_centre), reference_direction_(reference_direction) {
  shaft_line_ = vtkSmartPointer<vtkLineSource>::New();
  tip_a_ = vtkSmartPointer<vtkLineSource>::New();
  tip_b_ = vtkSmartPointer<vtkLineSource>::New();
  const double r = config.shaft_radius_m;
  shaft_ = Tube(shaft_line_, r);
  jaw_a_ = Tube(tip_a_, 0.45 * r);
  jaw_b_ = Tube(tip_b_, 0.45 * r);
  Steel(shaft_, kInsulationGrey);
  shaft_->GetProperty()->SetSpecular(0.5);  // a glossy plastic sleeve: highlights, no metal tint
  shaft_->GetProperty()->SetSpecularPower(30);
  glow_ = vtkSmartPointer<vtkSphereSource>::New();
  glow_->SetRadius(0.7 * r);
  glow_->SetThetaResolution(16);
  glow_->SetPhiResolution(12);
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(glow_->GetOutputPort());
  glow_actor_ = vtkSmartPointer<vtkActor>::New();
  glow_actor_->SetMapper(mapper);
  Emissive(glow_actor_, kCauteryGlowRgb);
  glow_actor_->VisibilityOff();
  actors_ = {shaft_, jaw_a_, jaw_b_, glow_actor_};
}

void InstrumentActors::Update(const InstrumentFrame& frame) {
  const auto& pose = frame.pose;
  const Eigen::Vector3d d = physics::ShaftDirection(reference_direction_, pose);
  // The physics tip is the working point: the closed jaws' ends, the hook's bend (where it burns).
  // The drawn shaft stops short of it by the jaw or hook stem length.
  const Eigen::Vector3d tip = remote_centre_ + (pose.insertion_m - std::max(frame.past_contact_m, 0.0)) * d;
  const double head_m = config_.kind == InstrumentKind::kGrasper ? kJawLength_m : kHookStem_m;
  const Eigen::Vector3d hinge = tip - head_m * d;
  const Eigen::Vector3d outside = remote_centre_ - (config_.shaft_length_m - pose.insertion_m) * d;
  shaft_line_->SetPoint1(ToDisplay(outside).data());
  shaft_line_->SetPoint2(ToDisplay(hinge).data());
  // A frame across the shaft, turned by roll.
  Eigen::Vector3d side = d.cross(Eigen::Vector3d::UnitZ());
  if (side.norm() < 1e-6) side = d.cross(Eigen::Vector3d::UnitX());
  side = Eigen::AngleAxisd(pose.roll_rad, d) * side.normalized();

  if (config_.kind == InstrumentKind::kGrasper) {
    // Two jaws hinged one jaw length behind the tip, opening symmetrically by the jaw angle.
    const double half = 0.5 * std::max(pose.jaw_angle_rad, 0.0);
    const Eigen::Vector3d a = hinge + kJawLength_m * (std::cos(half) * d + std::sin(half) * side);
    const Eigen::Vector3d b = hinge + kJawLength_m * (std::cos(half) * d - std::sin(half) * side);
    tip_a_->SetPoint1(ToDisplay(hinge).data());
    tip_a_->SetPoint2(ToDisplay(a).data());
    tip_b_->SetPoint1(ToDisplay(hinge).data());
    tip_b_->SetPoint2(ToDisplay(b).data());
    for (vtkActor* jaw : {jaw_a_.Get(), jaw_b_.Get()}) {
      if (frame.slipping)
        Emissive(jaw, kSlipRgb);
      else
        Steel(jaw, kJawGrey);
    }
    glow_actor_->VisibilityOff();
  } else {
    // The hook: a stem along the shaft, then a short foot sideways (the L that catches tissue).
    const Eigen::Vector3d bend = tip;
    const Eigen::Vector3d foot = bend + kHookFoot_m * side;
    tip_a_->SetPoint1(ToDisplay(hinge).data());
    tip_a_->SetPoint2(ToDisplay(bend).data());
    tip_b_->SetPoint1(ToDisplay(bend).data());
    tip_b_->SetPoint2(ToDisplay(foot).data());
    Steel(jaw_a_, kJawGrey);
    if (frame.cautery_active)
      Emissive(jaw_b_, kCauteryGlowRgb);
    else
      Steel(jaw_b_, kJawGrey);
    glow_->SetCenter(ToDisplay(bend).data());
    glow_actor_->SetVisibility(frame.cautery_active);
  }
}

}  // namespace vesica::app
