#include "app/render/membrane_sheet.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>

#include "app/render/burn_colours.h"
#include "app/render/display_frame.h"
#include "app/render/render_colours.h"

namespace vesica::app {

MembraneSheet::MembraneSheet() {
  poly_ = vtkSmartPointer<vtkPolyData>::New();
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(poly_);
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  actor_ = vtkSmartPointer<vtkActor>::New();
  actor_->SetMapper(mapper);
  actor_->ForceTranslucentOn();  // per-cell alpha: always in the translucent pass
  auto* prop = actor_->GetProperty();
  prop->SetAmbient(0.35);  // a thin sheet lets light through: less shading than the organs
  prop->SetDiffuse(0.65);
  prop->SetSpecular(0.2);
  prop->SetSpecularPower(20);
  actor_->VisibilityOff();
}

void MembraneSheet::Update(const physics::Vertices& vertices, const physics::Triangles& triangles,
                           const std::vector<float>& opacity, const std::vector<float>& burn) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(vertices.rows());
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) points->SetPoint(v, ToDisplay(vertices.row(v).transpose()).data());
  // Removed triangles are left out of the cells rather than drawn with alpha 0, so a cut
  // membrane leaves exactly the picture without it.
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("colour");
  colours->SetNumberOfComponents(4);
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const float o = opacity.empty() ? 1.0f : Unit(opacity[f]);
    const auto alpha = static_cast<unsigned char>(std::lround(255.0 * kMembraneAlpha * o));
    if (alpha == 0) continue;
    const vtkIdType ids[3] = {triangles(f, 0), triangles(f, 2), triangles(f, 1)};  // mirrored: reversed
    cells->InsertNextCell(3, ids);
    const auto c = BurnedColour(kMembraneRgb, 1.0, burn.empty() ? 0.0f : burn[f]);
    const unsigned char rgba[4] = {c[0], c[1], c[2], alpha};
    colours->InsertNextTypedTuple(rgba);
  }
  poly_->Initialize();
  poly_->SetPoints(points);
  poly_->SetPolys(cells);
  poly_->GetCellData()->SetScalars(colours);
  poly_->Modified();
  actor_->SetVisibility(cells->GetNumberOfCells() > 0);
}

}  // namespace vesica::app
