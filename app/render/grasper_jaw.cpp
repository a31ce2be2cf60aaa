#include "app/render/grasper_jaw.h"

#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace vesica::app {

namespace {

// Outline and window are superellipses |x/a|^4 + |z/b|^4 = 1 (a rounded rectangle): square
// enough to read as machined steel, round at the tip so the jaw is atraumatic.
constexpr double kExponent = 4.0;
constexpr int kOutlineSamples = 48;

double SuperellipseValue(double x, double z, double a, double b) {
  return std::pow(std::abs(x / a), kExponent) + std::pow(std::abs(z / b), kExponent);
}

// Point at angle theta on the superellipse with semi-axes a (x) and b (z).
void SuperellipsePoint(double theta, double a, double b, double& x, double& z) {
  const double c = std::cos(theta), s = std::sin(theta);
  x = a * std::copysign(std::pow(std::abs(c), 2.0 / kExponent), c);
  z = b * std::copysign(std::pow(std::abs(s), 2.0 / kExponent), s);
}

}  // namespace

bool InGrasperJawWindow(const GrasperJawShape& s, double x_m, double z_m) {
  return SuperellipseValue(x_m - 0.5 * s.length_m, z_m, 0.5 * s.window_length_m, 0.5 * s.window_width_m) < 1.0;
}

bool InGrasperJawOutline(const GrasperJawShape& s, double x_m, double z_m) {
  return SuperellipseValue(x_m - 0.5 * s.length_m, z_m, 0.5 * s.length_m, 0.5 * s.width_m) < 1.0;
}

vtkSmartPointer<vtkPolyData> MakeGrasperJaw(const GrasperJawShape& s) {
  if (!(s.window_length_m > 0 && s.window_width_m > 0 && s.window_length_m < s.length_m &&
        s.window_width_m < s.width_m && s.thickness_m > 0))
    throw std::invalid_argument("grasper jaw: the window must lie inside a blade of positive size");
  const int n = kOutlineSamples;
  auto points = vtkSmartPointer<vtkPoints>::New();
  // Four loops of n points: outer face, inner (window) face, outer back, inner back.
  for (const double y : {0.0, s.thickness_m})
    for (const bool outer : {true, false})
      for (int k = 0; k < n; ++k) {
        double x, z;
        const double a = 0.5 * (outer ? s.length_m : s.window_length_m);
        const double b = 0.5 * (outer ? s.width_m : s.window_width_m);
        SuperellipsePoint(2 * std::numbers::pi * k / n, a, b, x, z);
        points->InsertNextPoint(0.5 * s.length_m + x, y, z);
      }
  const auto id = [n](int loop, int k) { return static_cast<vtkIdType>(loop * n + (k % n)); };
  constexpr int kFaceOuter = 0, kFaceInner = 1, kBackOuter = 2, kBackInner = 3;
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  const auto quad = [&](vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType d) {
    const vtkIdType t1[3] = {a, b, c}, t2[3] = {a, c, d};
    cells->InsertNextCell(3, t1);
    cells->InsertNextCell(3, t2);
  };
  // Back, face, outer rim and window wall; vtkPolyDataNormals orients them all outward.
  for (int k = 0; k < n; ++k) {
    quad(id(kBackOuter, k), id(kBackInner, k), id(kBackInner, k + 1), id(kBackOuter, k + 1));  // back (+y)
    quad(id(kFaceOuter, k), id(kFaceOuter, k + 1), id(kFaceInner, k + 1), id(kFaceInner, k));  // face (-y)
    quad(id(kFaceOuter, k), id(kBackOuter, k), id(kBackOuter, k + 1), id(kFaceOuter, k + 1));  // rim
    quad(id(kFaceInner, k), id(kFaceInner, k + 1), id(kBackInner, k + 1), id(kBackInner, k));  // window wall
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();
  normals->SetInputData(poly);
  normals->SetFeatureAngle(50);  // sharp machined edges, smooth round rim
  normals->SplittingOn();
  normals->ConsistencyOn();
  normals->AutoOrientNormalsOn();  // closed surface: outward
  normals->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(normals->GetOutput());
  return out;
}

}  // namespace vesica::app
