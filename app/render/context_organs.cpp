#include "app/render/context_organs.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkSplineFilter.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkTubeFilter.h>

#include <cmath>

#include "app/render/display_frame.h"
#include "app/render/hidden_side_culling.h"
#include "app/render/material_model.h"

namespace vesica::app {

namespace {

vtkSmartPointer<vtkAlgorithm> Tube(const ContextOrgan& organ) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  for (const auto& p : organ.points_m) points->InsertNextPoint(ToDisplay(p).data());
  auto line = vtkSmartPointer<vtkCellArray>::New();
  line->InsertNextCell(static_cast<vtkIdType>(organ.points_m.size()));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(organ.points_m.size()); ++i) line->InsertCellPoint(i);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetLines(line);
  auto spline = vtkSmartPointer<vtkSplineFilter>::New();  // a smooth centreline through the points
  spline->SetInputData(poly);
  spline->SetSubdivideToLength();
  spline->SetLength(0.002);
  auto tube = vtkSmartPointer<vtkTubeFilter>::New();
  tube->SetInputConnection(spline->GetOutputPort());
  tube->SetRadius(organ.radius_m);
  tube->SetNumberOfSides(24);
  tube->CappingOn();
  return tube;
}

vtkSmartPointer<vtkAlgorithm> Ellipsoid(const ContextOrgan& organ) {
  auto sphere = vtkSmartPointer<vtkSphereSource>::New();
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(32);
  auto transform = vtkSmartPointer<vtkTransform>::New();
  const Eigen::Vector3d c = ToDisplay(organ.centre_m);
  transform->Translate(c.data());
  transform->Scale(organ.semi_axes_m.data());  // positive scales: the winding stays outward
  auto placed = vtkSmartPointer<vtkTransformPolyDataFilter>::New();
  placed->SetInputConnection(sphere->GetOutputPort());
  placed->SetTransform(transform);
  return placed;
}

}  // namespace

std::vector<vtkSmartPointer<vtkActor>> MakeContextOrganActors(const std::vector<ContextOrgan>& organs, bool pbr) {
  std::vector<vtkSmartPointer<vtkActor>> actors;
  for (const ContextOrgan& organ : organs) {
    auto source = organ.shape == ContextOrgan::Shape::kTube ? Tube(organ) : Ellipsoid(organ);
    auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();  // smooth shading across the facets
    normals->SetInputConnection(source->GetOutputPort());
    normals->SetFeatureAngle(80);
    // Built once and handed over as data, the mapper marked static: a pipeline behind each of
    // the dozen organs was re-checked (and its bounds asked for) every frame for nothing.
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    normals->Update();
    mapper->SetInputData(normals->GetOutput());
    mapper->StaticOn();
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    auto* p = actor->GetProperty();
    p->SetColor(organ.rgb.x(), organ.rgb.y(), organ.rgb.z());
    p->SetInterpolationToPhong();
    p->SetAmbient(0.1);
    p->SetDiffuse(0.85);
    p->SetSpecular(0.3);  // wet serosa, as the organs
    p->SetSpecularPower(35);
    if (pbr) {  // PBR wants linear colour: it gamma-encodes its result
      p->SetInterpolationToPBR();
      p->SetColor(std::pow(organ.rgb.x(), 2.2), std::pow(organ.rgb.y(), 2.2), std::pow(organ.rgb.z(), 2.2));
      p->SetAmbient(0.0);
      p->SetDiffuse(1.0);
      p->SetMetallic(0.0);
      p->SetRoughness(kContextRoughness);
    }
    actor->PickableOff();
    CullHiddenSide(actor, normals->GetOutput());  // closed organs seen from outside
    actors.push_back(actor);
  }
  return actors;
}

}  // namespace vesica::app
