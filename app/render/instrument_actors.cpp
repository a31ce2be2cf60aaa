#include "app/render/instrument_actors.h"

#include <vtkActor.h>
#include <vtkCubeSource.h>
#include <vtkLineSource.h>
#include <vtkMatrix4x4.h>
#include <vtkPolyData.h>
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
constexpr double kSteelGrey = 0.45;  // Phong: diffuse grey of brushed steel
// PBR steel: with one light and no environment map a fully metallic surface is black away from
// its highlight; partly metallic, it keeps a grey body as brushed steel under a scope does.
constexpr double kSteelBaseColour = 0.55;
constexpr double kSteelMetallic = 0.6;
constexpr double kSteelRoughness = 0.35;
constexpr double kPlasticRoughness = 0.35;

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
  return actor;
}

vtkSmartPointer<vtkActor> Solid(vtkPolyData* poly) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(poly);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

// Lit from inside: full ambient so it reads as light, not as a painted surface (Phong in both
// material models: PBR has no ambient term).
void Emissive(vtkActor* actor, const double rgb[3]) {
  auto* p = actor->GetProperty();
  p->SetInterpolationToGouraud();
  p->SetColor(rgb[0], rgb[1], rgb[2]);
  p->SetAmbient(1.0);
  p->SetDiffuse(0.3);
  p->SetSpecular(0.0);
}

// Places a part modelled in its own frame (x, y, z axes, display frame) at `origin`.
void Place(vtkActor* actor, const Eigen::Vector3d& origin, const Eigen::Vector3d& x, const Eigen::Vector3d& y,
           const Eigen::Vector3d& z) {
  auto m = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int r = 0; r < 3; ++r) {
    m->SetElement(r, 0, x(r));
    m->SetElement(r, 1, y(r));
    m->SetElement(r, 2, z(r));
    m->SetElement(r, 3, origin(r));
  }
  actor->SetUserMatrix(m);
}

}  // namespace

GrasperJawShape GrasperJawFor(double shaft_radius_m) {
  GrasperJawShape s;
  s.length_m = 0.018;
  s.width_m = 1.6 * shaft_radius_m;
  s.thickness_m = 0.6 * shaft_radius_m;
  s.window_length_m = 0.6 * s.length_m;
  s.window_width_m = 0.5 * s.width_m;
  return s;
}

void InstrumentActors::Steel(vtkActor* actor) const {
  auto* p = actor->GetProperty();
  if (pbr_) {
    p->SetInterpolationToPBR();
    p->SetColor(kSteelBaseColour, kSteelBaseColour, kSteelBaseColour * 1.02);
    p->SetMetallic(kSteelMetallic);
    p->SetRoughness(kSteelRoughness);
    p->SetAmbient(0.0);
    p->SetDiffuse(1.0);
    return;
  }
  p->SetInterpolationToGouraud();
  p->SetColor(kSteelGrey, kSteelGrey, kSteelGrey * 1.03);
  p->SetAmbient(0.0);
  p->SetDiffuse(1.0);
  p->SetSpecular(0.8);
  p->SetSpecularPower(60);
}

void InstrumentActors::Insulation(vtkActor* actor) const {
  auto* p = actor->GetProperty();
  p->SetColor(kInsulationGrey, kInsulationGrey, kInsulationGrey * 1.03);
  if (pbr_) {
    const double linear = std::pow(kInsulationGrey, 2.2);  // PBR lights in linear colour
    p->SetColor(linear, linear, linear * 1.03);
    p->SetInterpolationToPBR();
    p->SetMetallic(0.0);
    p->SetRoughness(kPlasticRoughness);
    return;
  }
  p->SetAmbient(0.0);
  p->SetDiffuse(1.0);
  p->SetSpecular(0.5);  // a glossy plastic sleeve: highlights, no metal tint
  p->SetSpecularPower(30);
}

InstrumentActors::InstrumentActors(const InstrumentConfig& config, const Eigen::Vector3d& remote_centre,
                                   const Eigen::Vector3d& reference_direction, bool pbr)
    : config_(config),
      remote_centre_(remote_centre),
      reference_direction_(reference_direction),
      pbr_(pbr),
      jaw_shape_(GrasperJawFor(config.shaft_radius_m)) {
  const double r = config.shaft_radius_m;
  shaft_line_ = vtkSmartPointer<vtkLineSource>::New();
  shaft_ = Tube(shaft_line_, r);
  Insulation(shaft_);
  if (config.kind == InstrumentKind::kGrasper) {
    const vtkSmartPointer<vtkPolyData> jaw = MakeGrasperJaw(jaw_shape_);
    jaw_a_ = Solid(jaw);
    jaw_b_ = Solid(jaw);
    Steel(jaw_a_);
    Steel(jaw_b_);
    actors_ = {shaft_, jaw_a_, jaw_b_};
    return;
  }
  sleeve_line_ = vtkSmartPointer<vtkLineSource>::New();
  stem_line_ = vtkSmartPointer<vtkLineSource>::New();
  foot_line_ = vtkSmartPointer<vtkLineSource>::New();
  sleeve_ = Tube(sleeve_line_, 0.45 * r);
  stem_ = Tube(stem_line_, 0.3 * r);
  foot_ = Tube(foot_line_, 0.3 * r);
  Insulation(sleeve_);
  Steel(stem_);
  Steel(foot_);
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
  actors_ = {shaft_, sleeve_, stem_, foot_, glow_actor_};
  BuildExchangeTools();
}

void InstrumentActors::BuildExchangeTools() {
  const double r = config_.shaft_radius_m;
  // The clip applier: slotted jaws (the clip rides in the slot), a little slimmer than a grasper's.
  GrasperJawShape applier;
  applier.length_m = kClipApplierJaw_m;
  applier.width_m = 1.3 * r;
  applier.thickness_m = 0.5 * r;
  applier.window_length_m = 0.8 * applier.length_m;
  applier.window_width_m = 0.25 * applier.width_m;
  const vtkSmartPointer<vtkPolyData> jaw = MakeGrasperJaw(applier);
  applier_a_ = Solid(jaw);
  applier_b_ = Solid(jaw);
  Steel(applier_a_);
  Steel(applier_b_);
  // A closed medium titanium clip: 9 mm long, 1 mm square, along its own x.
  auto clip = vtkSmartPointer<vtkCubeSource>::New();
  clip->SetXLength(0.009);
  clip->SetYLength(0.001);
  clip->SetZLength(0.001);
  clip->Update();
  loaded_clip_ = Solid(clip->GetOutput());
  Steel(loaded_clip_);
  // Scissors: two slender blades from the hinge (x), the cutting edge at y = 0.
  auto blade = vtkSmartPointer<vtkCubeSource>::New();
  blade->SetBounds(0, kScissorBlade_m, 0, 0.35 * r, -0.4 * r, 0.4 * r);
  blade->Update();
  blade_a_ = Solid(blade->GetOutput());
  blade_b_ = Solid(blade->GetOutput());
  Steel(blade_a_);
  Steel(blade_b_);
  for (const auto& a : {applier_a_, applier_b_, loaded_clip_, blade_a_, blade_b_}) {
    a->VisibilityOff();
    actors_.push_back(a);
  }
}

void InstrumentActors::PlaceJaws(vtkActor* a, vtkActor* b, const Eigen::Vector3d& hinge, const Eigen::Vector3d& d,
                                 const Eigen::Vector3d& side, double jaw_angle_rad, double length_m, double width_m) {
  const double half = 0.5 * std::max(jaw_angle_rad, 0.0);
  for (const int sign : {+1, -1}) {
    const Eigen::Vector3d along = std::cos(half) * d + sign * std::sin(half) * side;
    const Eigen::Vector3d back = -std::sin(half) * d * sign + std::cos(half) * side;  // away from the other jaw
    const Eigen::Vector3d x_D = ToDisplay(along), y_D = ToDisplay(sign * back);
    Place(sign > 0 ? a : b, ToDisplay(hinge), x_D, y_D, x_D.cross(y_D));
    casters_.push_back({ToDisplay(hinge + 0.15 * length_m * along), ToDisplay(hinge + 0.9 * length_m * along),
                        0.5 * width_m});
  }
}

void InstrumentActors::Update(const InstrumentFrame& frame) {
  const auto& pose = frame.pose;
  const Eigen::Vector3d d = physics::ShaftDirection(reference_direction_, pose);
  // The physics tip is the working point: the closed jaws' ends, the hook's bend (where it burns).
  // The drawn shaft stops short of it by the jaw or hook stem length.
  const Eigen::Vector3d tip = remote_centre_ + (pose.insertion_m - std::max(frame.past_contact_m, 0.0)) * d;
  const bool grasper = config_.kind == InstrumentKind::kGrasper;
  // The right hand's port holds what the frame says (a grasper there would be a bad frame).
  const InstrumentKind tool = !grasper && physics::IsRightHandTool(frame.tool) ? frame.tool : config_.kind;
  const double head_m = grasper                                ? jaw_shape_.length_m
                        : tool == InstrumentKind::kClipApplier ? kClipApplierJaw_m
                        : tool == InstrumentKind::kScissors    ? kScissorBlade_m
                                                               : kHookStem_m;
  const Eigen::Vector3d hinge = tip - head_m * d;
  const Eigen::Vector3d outside = remote_centre_ - (config_.shaft_length_m - pose.insertion_m) * d;
  shaft_line_->SetPoint1(ToDisplay(outside).data());
  shaft_line_->SetPoint2(ToDisplay(hinge).data());
  const double r = config_.shaft_radius_m;
  casters_.clear();
  casters_.push_back({ToDisplay(outside), ToDisplay(hinge), r});
  // A frame across the shaft, turned by roll.
  Eigen::Vector3d side = d.cross(Eigen::Vector3d::UnitZ());
  if (side.norm() < 1e-6) side = d.cross(Eigen::Vector3d::UnitX());
  side = Eigen::AngleAxisd(pose.roll_rad, d) * side.normalized();

  if (grasper) {
    // Two jaws hinged one jaw length behind the tip, opening symmetrically by the jaw angle in
    // the plane of d and side; each jaw's grasping face looks at the other's.
    const double half = 0.5 * std::max(pose.jaw_angle_rad, 0.0);
    for (const int sign : {+1, -1}) {
      const Eigen::Vector3d along = std::cos(half) * d + sign * std::sin(half) * side;
      const Eigen::Vector3d back = -std::sin(half) * d * sign + std::cos(half) * side;  // away from the other jaw
      const Eigen::Vector3d x_D = ToDisplay(along), y_D = ToDisplay(sign * back);
      vtkActor* jaw = sign > 0 ? jaw_a_.Get() : jaw_b_.Get();
      Place(jaw, ToDisplay(hinge), x_D, y_D, x_D.cross(y_D));
      if (frame.slipping)
        Emissive(jaw, kSlipRgb);
      else
        Steel(jaw);
      casters_.push_back({ToDisplay(hinge + 0.15 * jaw_shape_.length_m * along),
                          ToDisplay(hinge + 0.9 * jaw_shape_.length_m * along), 0.5 * jaw_shape_.width_m});
    }
    return;
  }
  const bool hook = tool == InstrumentKind::kCauteryHook;
  for (vtkActor* a : {sleeve_.Get(), stem_.Get(), foot_.Get()}) a->SetVisibility(hook);
  applier_a_->SetVisibility(tool == InstrumentKind::kClipApplier);
  applier_b_->SetVisibility(tool == InstrumentKind::kClipApplier);
  blade_a_->SetVisibility(tool == InstrumentKind::kScissors);
  blade_b_->SetVisibility(tool == InstrumentKind::kScissors);
  // A clip is loaded between the open jaws; closed, it has been fired (or the jaws are empty).
  loaded_clip_->SetVisibility(tool == InstrumentKind::kClipApplier && pose.jaw_angle_rad > 0.05);
  if (!hook) {
    glow_actor_->VisibilityOff();
    if (tool == InstrumentKind::kClipApplier) {
      PlaceJaws(applier_a_, applier_b_, hinge, d, side, pose.jaw_angle_rad, kClipApplierJaw_m, 1.3 * r);
      const Eigen::Vector3d centre = hinge + 0.6 * kClipApplierJaw_m * d;
      const Eigen::Vector3d x_D = ToDisplay(side), y_D = ToDisplay(d);  // across the opening
      Place(loaded_clip_, ToDisplay(centre), x_D, y_D, x_D.cross(y_D));
    } else {
      PlaceJaws(blade_a_, blade_b_, hinge, d, side, pose.jaw_angle_rad, kScissorBlade_m, 0.8 * r);
    }
    return;
  }
  // The hook: an insulated stem along the shaft, bare metal for its last millimetres, then a short
  // foot sideways (the L that catches tissue).
  const Eigen::Vector3d bend = tip;
  const Eigen::Vector3d bare = bend - kHookBareStem_m * d;
  const Eigen::Vector3d foot = bend + kHookFoot_m * side;
  sleeve_line_->SetPoint1(ToDisplay(hinge).data());
  sleeve_line_->SetPoint2(ToDisplay(bare).data());
  stem_line_->SetPoint1(ToDisplay(bare).data());
  stem_line_->SetPoint2(ToDisplay(bend).data());
  foot_line_->SetPoint1(ToDisplay(bend).data());
  foot_line_->SetPoint2(ToDisplay(foot).data());
  if (frame.cautery_active)
    Emissive(foot_, kCauteryGlowRgb);
  else
    Steel(foot_);
  glow_->SetCenter(ToDisplay(bend).data());
  glow_actor_->SetVisibility(frame.cautery_active);
  casters_.push_back({ToDisplay(hinge), ToDisplay(bend), 0.45 * r});
  casters_.push_back({ToDisplay(bend), ToDisplay(foot), 0.3 * r});
}

}  // namespace vesica::app
