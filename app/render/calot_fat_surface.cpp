#include "app/render/calot_fat_surface.h"

#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::app {

namespace {

// Each cell's bump reaches this many cell sizes: beyond one, so neighbours overlap and merge.
constexpr double kReachCells = 2.0;
// The surface passes where the density is this share of a filled lattice's (7.9 bumps): about
// 0.96 cell sizes out from the outermost intact cells' centres, so where the cells within a tube's
// radius + 2 mm (one cell) of the sight lines to it are gone the tube shows; a row of cells still
// draws a strand, a lone cell (one bump) nothing.
constexpr double kLevelOfFilled = 0.25;
// Density samples per cell edge: the cells' own lattice. Shaded with the density's gradient the
// surface looks as smooth as on a grid twice as fine, whose rebuild cost 3.7 times as much
// (bench/render/calot_fat_surface_bench.cpp).
constexpr int kSamplesPerCell = 1;

// The bump: smooth (zero slope at its reach), compact, 1 at the cell's centre.
double Bump(double r2, double reach2) {
  if (r2 >= reach2) return 0.0;
  const double u = 1.0 - r2 / reach2;
  return u * u;
}

// Density inside a filled lattice of spacing 1: the sum of the bumps of every lattice point.
double FilledDensity() {
  const int n = static_cast<int>(std::ceil(kReachCells));
  double sum = 0.0;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) sum += Bump(i * i + j * j + k * k, kReachCells * kReachCells);
  return sum;
}

}  // namespace

CalotFatSurface::CalotFatSurface() : surface_(vtkSmartPointer<vtkPolyData>::New()) {}

CalotFatSurface::~CalotFatSurface() = default;

vtkPolyData* CalotFatSurface::surface() const { return surface_.Get(); }

void CalotFatSurface::Update(const std::vector<Eigen::Vector3d>& rest_D, const std::vector<Eigen::Vector3d>& now_D,
                             double cell_m) {
  if (rest_D.size() != now_D.size())
    throw std::invalid_argument("CalotFatSurface: " + std::to_string(rest_D.size()) + " rest places for " +
                                std::to_string(now_D.size()) + " fat cells");
  if (!(cell_m > 0))
    throw std::invalid_argument("CalotFatSurface: cell size " + std::to_string(cell_m) + " m, not > 0");
  if (rest_D != rest_D_ || cell_m != cell_m_) {
    Rebuild(rest_D, cell_m);
    rest_D_ = rest_D;
    cell_m_ = cell_m;
    now_D_.clear();
  }
  if (now_D != now_D_) {
    Move(rest_D, now_D);
    now_D_ = now_D;
  }
}

void CalotFatSurface::Rebuild(const std::vector<Eigen::Vector3d>& rest_D, double cell_m) {
  ++rebuilds_;
  vertices_rest_D_.clear();
  offsets_.assign(1, 0);
  cells_.clear();
  weights_.clear();
  surface_->Initialize();
  if (rest_D.empty()) {
    surface_->Modified();
    return;
  }
  const double reach_m = kReachCells * cell_m, reach2 = reach_m * reach_m;
  const double sample_m = cell_m / kSamplesPerCell;

  // The density on a grid round the cells.
  Eigen::Vector3d lo = rest_D.front(), hi = rest_D.front();
  for (const Eigen::Vector3d& p : rest_D) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo.array() -= reach_m + sample_m;
  hi.array() += reach_m + sample_m;
  const Eigen::Vector3i dims = ((hi - lo) / sample_m).array().ceil().cast<int>() + 1;
  std::vector<float> density(static_cast<std::size_t>(dims.prod()), 0.0f);
  const int span = static_cast<int>(std::ceil(reach_m / sample_m));
  for (const Eigen::Vector3d& p : rest_D) {
    const Eigen::Vector3d g = (p - lo) / sample_m;
    const Eigen::Vector3i c = g.array().round().cast<int>();
    for (int k = std::max(0, c.z() - span); k <= std::min(dims.z() - 1, c.z() + span); ++k)
      for (int j = std::max(0, c.y() - span); j <= std::min(dims.y() - 1, c.y() + span); ++j)
        for (int i = std::max(0, c.x() - span); i <= std::min(dims.x() - 1, c.x() + span); ++i) {
          const double r2 = ((Eigen::Vector3d(i, j, k) - g) * sample_m).squaredNorm();
          density[static_cast<std::size_t>(i + dims.x() * (j + dims.y() * k))] += static_cast<float>(Bump(r2, reach2));
        }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims.x(), dims.y(), dims.z());
  image->SetOrigin(lo.x(), lo.y(), lo.z());
  image->SetSpacing(sample_m, sample_m, sample_m);
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName("density");
  values->SetArray(density.data(), static_cast<vtkIdType>(density.size()), 1);  // density outlives the filter
  image->GetPointData()->SetScalars(values);

  static const double kFilled = FilledDensity();
  auto contour = vtkSmartPointer<vtkFlyingEdges3D>::New();
  contour->SetInputData(image);
  contour->SetValue(0, kLevelOfFilled * kFilled);
  contour->ComputeNormalsOn();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->Update();
  surface_->DeepCopy(contour->GetOutput());
  surface_->GetPointData()->SetScalars(nullptr);

  // Each vertex carried by the cells whose bumps reach it, weighted as their density there: the
  // cells on the 4 x 4 x 4 lattice places round it (the nearest 64; farther ones weigh little).
  const Eigen::Vector3i lattice = ((hi - lo) / cell_m).array().ceil().cast<int>() + 1;
  std::vector<int> cell_at(static_cast<std::size_t>(lattice.prod()), -1);
  auto at = [&](int i, int j, int k) -> int& {
    return cell_at[static_cast<std::size_t>(i + lattice.x() * (j + lattice.y() * k))];
  };
  for (std::size_t c = 0; c < rest_D.size(); ++c) {
    const Eigen::Vector3i l = ((rest_D[c] - lo) / cell_m).array().round().cast<int>();
    at(l.x(), l.y(), l.z()) = static_cast<int>(c);  // inside: lo and hi pad the cells
  }
  vtkPoints* points = surface_->GetPoints();
  const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
  vertices_rest_D_.resize(static_cast<std::size_t>(n));
  for (vtkIdType v = 0; v < n; ++v) {
    double x[3];
    points->GetPoint(v, x);
    const Eigen::Vector3d p(x[0], x[1], x[2]);
    vertices_rest_D_[static_cast<std::size_t>(v)] = p;
    const Eigen::Vector3i base = ((p - lo) / cell_m).array().floor().cast<int>();
    const std::size_t first = weights_.size();
    double total = 0.0;
    for (int k = std::max(0, base.z() - 1); k <= std::min(lattice.z() - 1, base.z() + 2); ++k)
      for (int j = std::max(0, base.y() - 1); j <= std::min(lattice.y() - 1, base.y() + 2); ++j)
        for (int i = std::max(0, base.x() - 1); i <= std::min(lattice.x() - 1, base.x() + 2); ++i) {
          const int c = at(i, j, k);
          if (c < 0) continue;
          const double w = Bump((rest_D[static_cast<std::size_t>(c)] - p).squaredNorm(), reach2);
          if (w <= 0) continue;
          cells_.push_back(c);
          weights_.push_back(w);
          total += w;
        }
    for (std::size_t e = first; e < weights_.size(); ++e) weights_[e] /= total;
    offsets_.push_back(static_cast<int>(weights_.size()));
  }
  surface_->Modified();
}

void CalotFatSurface::Move(const std::vector<Eigen::Vector3d>& rest_D, const std::vector<Eigen::Vector3d>& now_D) {
  vtkPoints* points = surface_->GetPoints();
  if (points == nullptr) return;
  for (std::size_t v = 0; v < vertices_rest_D_.size(); ++v) {
    Eigen::Vector3d p = vertices_rest_D_[v];
    for (int e = offsets_[v]; e < offsets_[v + 1]; ++e) {
      const auto c = static_cast<std::size_t>(cells_[static_cast<std::size_t>(e)]);
      p += weights_[static_cast<std::size_t>(e)] * (now_D[c] - rest_D[c]);
    }
    points->SetPoint(static_cast<vtkIdType>(v), p.data());
  }
  points->Modified();
  surface_->Modified();
}

}  // namespace vesica::app
