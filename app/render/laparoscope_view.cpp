#include "app/render/laparoscope_view.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkLight.h>
#include <vtkLineSource.h>
#include <vtkPNGWriter.h>
#include <vtkPoints.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTubeFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace vesica::app {

namespace {

template <typename T>
using Ptr = vtkSmartPointer<T>;

// Smooth, deterministic mottling so organs do not look like plastic: a few incommensurate waves.
double Mottle(const Eigen::Vector3d& p) {
  const double k = 180.0;  // ~3.5 cm wavelength in metres^-1
  return 0.5 * std::sin(k * p.x() + 1.3) * std::sin(0.7 * k * p.y() + 0.4) +
         0.5 * std::sin(1.9 * k * p.z() + 2.1 * std::sin(0.5 * k * p.x()));
}

Ptr<vtkPolyData> ToPolyData(const physics::TriangleMesh& mesh, const double rgb[3], double mottle_amplitude) {
  auto points = Ptr<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.num_vertices());
  auto colours = Ptr<vtkUnsignedCharArray>::New();
  colours->SetName("colour");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d p = mesh.vertices.row(i);
    points->SetPoint(i, p.data());
    const double shade = 1.0 + mottle_amplitude * Mottle(p);
    for (int c = 0; c < 3; ++c)
      colours->SetComponent(i, c, std::clamp(255.0 * rgb[c] * shade, 0.0, 255.0));
  }
  auto cells = Ptr<vtkCellArray>::New();
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const vtkIdType ids[3] = {mesh.triangles(f, 0), mesh.triangles(f, 1), mesh.triangles(f, 2)};
    cells->InsertNextCell(3, ids);
  }
  auto poly = Ptr<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  poly->GetPointData()->SetScalars(colours);
  return poly;
}

Ptr<vtkActor> OrganActor(const physics::TriangleMesh& mesh, const double rgb[3], double opacity) {
  auto normals = Ptr<vtkPolyDataNormals>::New();
  normals->SetInputData(ToPolyData(mesh, rgb, 0.12));
  normals->SplittingOff();
  normals->ConsistencyOn();
  auto mapper = Ptr<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->SetScalarModeToUsePointData();
  mapper->SetColorModeToDirectScalars();
  auto actor = Ptr<vtkActor>::New();
  actor->SetMapper(mapper);
  auto* prop = actor->GetProperty();
  prop->SetInterpolationToPhong();
  prop->SetAmbient(0.12);
  prop->SetDiffuse(0.85);
  prop->SetSpecular(0.35);  // wet serosa
  prop->SetSpecularPower(40);
  prop->SetOpacity(opacity);
  return actor;
}

// One instrument: a steel shaft (tube) and its tip (two jaws, or an L-shaped hook).
struct InstrumentActors {
  InstrumentConfig config;
  Eigen::Vector3d remote_centre;
  Eigen::Vector3d reference_direction;
  Ptr<vtkLineSource> shaft_line = Ptr<vtkLineSource>::New();
  Ptr<vtkLineSource> tip_a = Ptr<vtkLineSource>::New();
  Ptr<vtkLineSource> tip_b = Ptr<vtkLineSource>::New();
  std::vector<Ptr<vtkActor>> actors;

  static Ptr<vtkActor> Tube(vtkLineSource* line, double radius, double grey) {
    auto tube = Ptr<vtkTubeFilter>::New();
    tube->SetInputConnection(line->GetOutputPort());
    tube->SetRadius(radius);
    tube->SetNumberOfSides(16);
    tube->CappingOn();
    auto mapper = Ptr<vtkPolyDataMapper>::New();
    mapper->SetInputConnection(tube->GetOutputPort());
    auto actor = Ptr<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(grey, grey, grey * 1.03);
    actor->GetProperty()->SetSpecular(0.8);
    actor->GetProperty()->SetSpecularPower(60);
    return actor;
  }

  void Build() {
    const double r = config.shaft_radius_m;
    actors = {Tube(shaft_line, r, 0.55), Tube(tip_a, 0.45 * r, 0.35), Tube(tip_b, 0.45 * r, 0.35)};
  }

  void Update(const physics::InstrumentPose& pose) {
    const Eigen::Vector3d d = physics::ShaftDirection(reference_direction, pose);
    const Eigen::Vector3d tip = remote_centre + pose.insertion_m * d;
    const Eigen::Vector3d outside = remote_centre - (config.shaft_length_m - pose.insertion_m) * d;
    shaft_line->SetPoint1(outside.data());
    shaft_line->SetPoint2(tip.data());
    // A frame across the shaft, turned by roll.
    Eigen::Vector3d side = d.cross(Eigen::Vector3d::UnitZ());
    if (side.norm() < 1e-6) side = d.cross(Eigen::Vector3d::UnitX());
    side = Eigen::AngleAxisd(pose.roll_rad, d) * side.normalized();
    const double jaw_length = 0.018;
    if (config.kind == InstrumentKind::kGrasper) {
      const double half = 0.5 * pose.jaw_angle_rad;
      const Eigen::Vector3d a = tip + jaw_length * (std::cos(half) * d + std::sin(half) * side);
      const Eigen::Vector3d b = tip + jaw_length * (std::cos(half) * d - std::sin(half) * side);
      tip_a->SetPoint1(tip.data());
      tip_a->SetPoint2(a.data());
      tip_b->SetPoint1(tip.data());
      tip_b->SetPoint2(b.data());
    } else {
      const Eigen::Vector3d bend = tip + 0.012 * d;
      const Eigen::Vector3d hook = bend + 0.006 * side;
      tip_a->SetPoint1(tip.data());
      tip_a->SetPoint2(bend.data());
      tip_b->SetPoint1(bend.data());
      tip_b->SetPoint2(hook.data());
    }
  }
};

}  // namespace

struct LaparoscopeView::Impl {
  Ptr<vtkRenderer> renderer = Ptr<vtkRenderer>::New();
  std::vector<InstrumentActors> instruments;
  std::vector<physics::InstrumentPose> poses;
};

LaparoscopeView::LaparoscopeView(const Scenario& scenario, const SceneMeshes& meshes)
    : impl_(std::make_unique<Impl>()) {
  auto& r = *impl_->renderer;
  r.SetBackground(0.10, 0.03, 0.03);  // the cavity beyond the light's reach
  r.AddActor(OrganActor(meshes.liver, kLiverRgb, 1.0));
  r.AddActor(OrganActor(meshes.gallbladder_surface, kGallbladderRgb, 1.0));
  if (scenario.abdominal_wall.opacity > 0) {
    constexpr double kWallRgb[3] = {0.75, 0.45, 0.40};
    r.AddActor(OrganActor(meshes.abdominal_wall, kWallRgb, scenario.abdominal_wall.opacity));
  }

  const auto& scope = scenario.laparoscope;
  for (const auto& config : scenario.instruments) {
    InstrumentActors ia;
    ia.config = config;
    ia.remote_centre = scenario.trocar(config.trocar).position_m;
    ia.reference_direction = (scope.look_at_m - ia.remote_centre).normalized();
    ia.Build();
    const auto pose = physics::AimAt(ia.remote_centre, scope.look_at_m, config.initial_insertion_m,
                                     ia.reference_direction);
    ia.Update(pose);
    for (auto& a : ia.actors) r.AddActor(a);
    impl_->poses.push_back(pose);
    impl_->instruments.push_back(std::move(ia));
  }

  // The laparoscope: camera at the port looking at the target, cranial up, its own light.
  vtkCamera* camera = r.GetActiveCamera();
  camera->SetPosition(scope.position_m.data());
  camera->SetFocalPoint(scope.look_at_m.data());
  camera->SetViewUp(0, 0, 1);
  camera->OrthogonalizeViewUp();
  camera->SetViewAngle(scope.view_angle_deg);
  r.ResetCameraClippingRange();
  r.RemoveAllLights();
  auto light = Ptr<vtkLight>::New();
  light->SetLightTypeToHeadlight();
  light->SetIntensity(1.1);
  r.AddLight(light);
}

LaparoscopeView::~LaparoscopeView() = default;

vtkRenderer* LaparoscopeView::renderer() { return impl_->renderer; }

const std::vector<physics::InstrumentPose>& LaparoscopeView::poses() const { return impl_->poses; }

void LaparoscopeView::SetInstrumentPose(std::size_t instrument, const physics::InstrumentPose& pose) {
  impl_->poses.at(instrument) = pose;
  impl_->instruments.at(instrument).Update(pose);
}

void RenderToPng(LaparoscopeView& view, int width, int height, int frames, const std::filesystem::path& png) {
  auto window = Ptr<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);  // translucent actors vanish with multisampling on Mesa (shared notes)
  window->SetSize(width, height);
  window->AddRenderer(view.renderer());
  for (int i = 0; i < std::max(frames, 1); ++i) window->Render();
  auto grab = Ptr<vtkWindowToImageFilter>::New();
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  auto writer = Ptr<vtkPNGWriter>::New();
  writer->SetFileName(png.string().c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  window->RemoveRenderer(view.renderer());
  if (writer->GetErrorCode() != 0 || !std::filesystem::exists(png))
    throw std::runtime_error(png.string() + ": could not write PNG");
}

}  // namespace vesica::app
