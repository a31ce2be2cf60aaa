#include "app/render/membrane_sheet.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <numeric>

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
  cells_.clear();
  rgba_.clear();
  centroids_D_.clear();
  bounds_D_ = DisplayBounds{};
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const float o = opacity.empty() ? 1.0f : Unit(opacity[f]);
    const auto alpha = static_cast<unsigned char>(std::lround(255.0 * kMembraneAlpha * o));
    if (alpha == 0) continue;
    cells_.push_back({triangles(f, 0), triangles(f, 2), triangles(f, 1)});  // mirrored: reversed
    const auto c = BurnedColour(kMembraneRgb, 1.0, burn.empty() ? 0.0f : burn[f]);
    rgba_.push_back({c[0], c[1], c[2], alpha});
    Eigen::Vector3d centroid_D = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p_D = ToDisplay(vertices.row(triangles(f, k)).transpose());
      centroid_D += p_D;
      bounds_D_.Extend(p_D);  // as VTK bounds a polydata: by the points its cells use
    }
    centroids_D_.push_back(centroid_D / 3.0);
  }
  order_.resize(cells_.size());
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  poly_->Initialize();
  poly_->SetPoints(points);
  WriteCells();
  actor_->SetVisibility(!cells_.empty());
}

void MembraneSheet::SortBackToFront(const Eigen::Vector3d& eye_D) {
  if (cells_.empty()) return;
  scratch_order_.resize(cells_.size());
  std::iota(scratch_order_.begin(), scratch_order_.end(), std::size_t{0});
  std::vector<double> distance2(cells_.size());
  for (std::size_t i = 0; i < cells_.size(); ++i) distance2[i] = (centroids_D_[i] - eye_D).squaredNorm();
  std::stable_sort(scratch_order_.begin(), scratch_order_.end(),
                   [&](std::size_t a, std::size_t b) { return distance2[a] > distance2[b]; });
  if (scratch_order_ == order_) return;  // unchanged: nothing to upload
  order_.swap(scratch_order_);
  WriteCells();
}

void MembraneSheet::WriteCells() {
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("colour");
  colours->SetNumberOfComponents(4);
  colours->SetNumberOfTuples(static_cast<vtkIdType>(order_.size()));
  for (std::size_t i = 0; i < order_.size(); ++i) {
    cells->InsertNextCell(3, cells_[order_[i]].data());
    colours->SetTypedTuple(static_cast<vtkIdType>(i), rgba_[order_[i]].data());
  }
  poly_->SetPolys(cells);
  poly_->GetCellData()->SetScalars(colours);
  poly_->Modified();
}

}  // namespace vesica::app
