#include "app/render/calot_actors.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCubeSource.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkTubeFilter.h>
#include <vtkUnsignedCharArray.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "app/render/display_frame.h"

namespace vesica::app {

namespace {

constexpr double kFatRgb[3] = {0.88, 0.74, 0.38};   // as the context fat over the triangle
constexpr double kClipRgb[3] = {0.80, 0.80, 0.83};  // titanium
constexpr double kClipWidth_m = 0.0012, kClipThickness_m = 0.0008, kClipOverhang_m = 0.0015;
constexpr double kLeakRadius_m = 0.0025;

void Unit(vtkProperty* p, const double rgb[3], bool pbr, double roughness, double metallic = 0.0) {
  p->SetInterpolationToPhong();
  p->SetColor(rgb[0], rgb[1], rgb[2]);
  p->SetAmbient(0.1);
  p->SetDiffuse(0.85);
  p->SetSpecular(metallic > 0 ? 0.8 : 0.3);
  p->SetSpecularPower(metallic > 0 ? 60 : 35);
  if (pbr) {  // linear colour: PBR gamma-encodes its result
    p->SetInterpolationToPBR();
    p->SetColor(std::pow(rgb[0], 2.2), std::pow(rgb[1], 2.2), std::pow(rgb[2], 2.2));
    p->SetAmbient(0.0);
    p->SetDiffuse(1.0);
    p->SetMetallic(metallic);
    p->SetRoughness(roughness);
  }
}

vtkSmartPointer<vtkActor> ActorOf(vtkMapper* mapper) {
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->PickableOff();
  return actor;
}

unsigned char Byte(double v) { return static_cast<unsigned char>(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); }

}  // namespace

Eigen::Vector3d CalotTubeColour(physics::calot::TubeKind kind) {
  return kind == physics::calot::TubeKind::kCysticArtery ? Eigen::Vector3d(0.70, 0.16, 0.12)
                                                         : Eigen::Vector3d(0.62, 0.64, 0.42);
}

CalotActors::CalotActors(bool pbr)
    : tube_lines_(vtkSmartPointer<vtkPolyData>::New()),
      clip_points_(vtkSmartPointer<vtkPolyData>::New()),
      leak_points_(vtkSmartPointer<vtkPolyData>::New()) {
  // Tubes: each piece a polyline, its radius and colour per point.
  auto tube = vtkSmartPointer<vtkTubeFilter>::New();
  tube->SetInputData(tube_lines_);
  tube->SetVaryRadiusToVaryRadiusByAbsoluteScalar();
  tube->SetNumberOfSides(16);
  tube->CappingOn();
  auto tube_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  tube_mapper->SetInputConnection(tube->GetOutputPort());
  tube_mapper->SetScalarModeToUsePointFieldData();
  tube_mapper->SelectColorArray("rgb");
  tube_mapper->SetColorModeToDirectScalars();
  tube_mapper->ScalarVisibilityOn();
  auto tubes = ActorOf(tube_mapper);
  const double white[3] = {1, 1, 1};
  Unit(tubes->GetProperty(), white, pbr, 0.35);

  // Clips: a titanium bar across the tube.
  auto bar = vtkSmartPointer<vtkCubeSource>::New();
  auto clip_mapper = vtkSmartPointer<vtkGlyph3DMapper>::New();
  clip_mapper->SetInputData(clip_points_);
  clip_mapper->SetSourceConnection(bar->GetOutputPort());
  clip_mapper->SetOrientationArray("orientation");
  clip_mapper->SetOrientationModeToQuaternion();
  clip_mapper->SetScaleArray("size");
  clip_mapper->SetScaleModeToScaleByVectorComponents();
  clip_mapper->ScalarVisibilityOff();
  auto clips = ActorOf(clip_mapper);
  Unit(clips->GetProperty(), kClipRgb, pbr, 0.3, 1.0);

  // Fat: one smooth layer over the intact cells, wet peritoneum over yellow fat.
  auto fat_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  fat_mapper->SetInputData(fat_.surface());
  fat_mapper->ScalarVisibilityOff();
  auto fat = ActorOf(fat_mapper);
  Unit(fat->GetProperty(), kFatRgb, pbr, 0.4);

  // Leaks: a pool of blood or bile at the open end.
  auto pool = vtkSmartPointer<vtkSphereSource>::New();
  pool->SetRadius(kLeakRadius_m);
  pool->SetThetaResolution(16);
  pool->SetPhiResolution(12);
  auto leak_mapper = vtkSmartPointer<vtkGlyph3DMapper>::New();
  leak_mapper->SetInputData(leak_points_);
  leak_mapper->SetSourceConnection(pool->GetOutputPort());
  leak_mapper->ScalingOff();
  leak_mapper->SetScalarModeToUsePointFieldData();
  leak_mapper->SelectColorArray("rgb");
  leak_mapper->SetColorModeToDirectScalars();
  leak_mapper->ScalarVisibilityOn();
  auto leaks = ActorOf(leak_mapper);
  Unit(leaks->GetProperty(), white, pbr, 0.15);  // wet and glossy

  actors_ = {tubes, clips, fat, leaks};
  Update({});
}

CalotActors::~CalotActors() = default;

std::vector<vtkActor*> CalotActors::actors() const {
  std::vector<vtkActor*> out;
  for (const auto& a : actors_) out.push_back(a.Get());
  return out;
}

void CalotActors::Update(const CalotDrawing& drawing) {
  {  // tubes
    auto points = vtkSmartPointer<vtkPoints>::New();
    auto lines = vtkSmartPointer<vtkCellArray>::New();
    auto radius = vtkSmartPointer<vtkDoubleArray>::New();
    radius->SetName("radius");
    auto rgb = vtkSmartPointer<vtkUnsignedCharArray>::New();
    rgb->SetName("rgb");
    rgb->SetNumberOfComponents(3);
    for (const CalotTubeDrawing& t : drawing.tubes) {
      if (t.centreline_W.size() < 2) continue;
      const Eigen::Vector3d c = CalotTubeColour(t.kind);
      lines->InsertNextCell(static_cast<vtkIdType>(t.centreline_W.size()));
      for (const Eigen::Vector3d& p : t.centreline_W) {
        lines->InsertCellPoint(points->InsertNextPoint(ToDisplay(p).data()));
        radius->InsertNextValue(t.radius_m);
        rgb->InsertNextTuple3(Byte(c.x()), Byte(c.y()), Byte(c.z()));
      }
    }
    tube_lines_->Initialize();
    tube_lines_->SetPoints(points);
    tube_lines_->SetLines(lines);
    tube_lines_->GetPointData()->SetScalars(radius);
    tube_lines_->GetPointData()->AddArray(rgb);
    tube_lines_->Modified();
  }
  {  // clips: the bar's x across the tube, y along it, z through it (it closes round the tube)
    auto points = vtkSmartPointer<vtkPoints>::New();
    auto orientation = vtkSmartPointer<vtkDoubleArray>::New();
    orientation->SetName("orientation");
    orientation->SetNumberOfComponents(4);
    auto size = vtkSmartPointer<vtkDoubleArray>::New();
    size->SetName("size");
    size->SetNumberOfComponents(3);
    for (const CalotClipDrawing& c : drawing.clips) {
      const Eigen::Vector3d along = ToDisplay(c.along_W).normalized();
      Eigen::Vector3d across = along.cross(Eigen::Vector3d::UnitY());
      if (across.norm() < 1e-6) across = along.cross(Eigen::Vector3d::UnitZ());
      across.normalize();
      Eigen::Matrix3d r;
      r << across, along, across.cross(along);
      const Eigen::Quaterniond q(r);
      points->InsertNextPoint(ToDisplay(c.p_W).data());
      orientation->InsertNextTuple4(q.w(), q.x(), q.y(), q.z());
      size->InsertNextTuple3(2 * c.tube_radius_m + 2 * kClipOverhang_m, kClipWidth_m,
                             2 * c.tube_radius_m + 2 * kClipThickness_m);
    }
    clip_points_->Initialize();
    clip_points_->SetPoints(points);
    clip_points_->GetPointData()->AddArray(orientation);
    clip_points_->GetPointData()->AddArray(size);
    clip_points_->Modified();
  }
  {  // fat: the cells' rest places default to where they are
    std::vector<Eigen::Vector3d> now_D, rest_D;
    now_D.reserve(drawing.fat_cells_W.size());
    for (const Eigen::Vector3d& p : drawing.fat_cells_W) now_D.push_back(ToDisplay(p));
    if (drawing.fat_cells_rest_W.empty()) {
      rest_D = now_D;
    } else {
      rest_D.reserve(drawing.fat_cells_rest_W.size());
      for (const Eigen::Vector3d& p : drawing.fat_cells_rest_W) rest_D.push_back(ToDisplay(p));
    }
    fat_.Update(rest_D, now_D, drawing.fat_cell_size_m);
  }
  {  // leaks
    auto points = vtkSmartPointer<vtkPoints>::New();
    auto rgb = vtkSmartPointer<vtkUnsignedCharArray>::New();
    rgb->SetName("rgb");
    rgb->SetNumberOfComponents(3);
    for (const CalotLeakDrawing& l : drawing.leaks) {
      points->InsertNextPoint(ToDisplay(l.p_W).data());
      if (l.blood)
        rgb->InsertNextTuple3(115, 5, 5);  // fresh blood, dark red
      else
        rgb->InsertNextTuple3(140, 150, 40);  // bile, green-yellow
    }
    leak_points_->Initialize();
    leak_points_->SetPoints(points);
    leak_points_->GetPointData()->AddArray(rgb);
    leak_points_->Modified();
  }
}

}  // namespace vesica::app
