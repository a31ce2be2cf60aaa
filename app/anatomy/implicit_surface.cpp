#include "app/anatomy/implicit_surface.h"

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkClipPolyData.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkMarchingCubes.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>
#include <vtkPolyDataNormals.h>
#include <vtkQuadricDecimation.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vesica::app::anatomy {

namespace {

using physics::TriangleMesh;

vtkSmartPointer<vtkPolyData> ToPolyData(const TriangleMesh& mesh) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    points->SetPoint(i, mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  }
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const vtkIdType ids[3] = {mesh.triangles(f, 0), mesh.triangles(f, 1), mesh.triangles(f, 2)};
    polys->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  return poly;
}

// Triangles only; unused points are dropped by the cleaning step that precedes every call.
TriangleMesh FromPolyData(vtkPolyData* poly) {
  TriangleMesh mesh;
  mesh.vertices.resize(poly->GetNumberOfPoints(), 3);
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    double p[3];
    poly->GetPoint(i, p);
    mesh.vertices.row(i) << p[0], p[1], p[2];
  }
  vtkCellArray* polys = poly->GetPolys();
  mesh.triangles.resize(polys->GetNumberOfCells(), 3);
  auto ids = vtkSmartPointer<vtkIdList>::New();
  int f = 0;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) throw std::runtime_error("surface pipeline: non-triangle cell");
    mesh.triangles.row(f++) << static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(1)),
        static_cast<int>(ids->GetId(2));
  }
  mesh.triangles.conservativeResize(f, 3);
  return mesh;
}

vtkSmartPointer<vtkPolyData> CleanTriangulate(vtkPolyData* input) {
  auto clean = vtkSmartPointer<vtkCleanPolyData>::New();
  clean->SetInputData(input);
  clean->PointMergingOn();
  clean->SetTolerance(0.0);
  auto triangles = vtkSmartPointer<vtkTriangleFilter>::New();
  triangles->SetInputConnection(clean->GetOutputPort());
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  return triangles->GetOutput();
}

}  // namespace

TriangleMesh ExtractIsosurface(const ImplicitField& field, const Box& box, double voxel_size_m) {
  if (!(voxel_size_m > 0)) throw std::invalid_argument("ExtractIsosurface: voxel size must be > 0");
  const Eigen::Vector3d origin = box.min_m - Eigen::Vector3d::Constant(2 * voxel_size_m);
  const Eigen::Vector3d extent = box.max_m - box.min_m;
  int dims[3];
  for (int k = 0; k < 3; ++k) dims[k] = static_cast<int>(std::ceil(extent[k] / voxel_size_m)) + 5;

  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims);
  image->SetOrigin(origin.data());
  image->SetSpacing(voxel_size_m, voxel_size_m, voxel_size_m);
  auto values = vtkSmartPointer<vtkDoubleArray>::New();
  values->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  vtkIdType n = 0;
  for (int k = 0; k < dims[2]; ++k) {
    for (int j = 0; j < dims[1]; ++j) {
      for (int i = 0; i < dims[0]; ++i) {
        const Eigen::Vector3d p = origin + voxel_size_m * Eigen::Vector3d(i, j, k);
        values->SetValue(n++, field(p));
      }
    }
  }
  image->GetPointData()->SetScalars(values);

  // vtkMarchingCubes is serial: the output order does not depend on the thread count.
  auto cubes = vtkSmartPointer<vtkMarchingCubes>::New();
  cubes->SetInputData(image);
  cubes->SetValue(0, 0.0);
  cubes->ComputeNormalsOff();
  cubes->ComputeGradientsOff();
  cubes->ComputeScalarsOff();
  auto largest = vtkSmartPointer<vtkPolyDataConnectivityFilter>::New();
  largest->SetInputConnection(cubes->GetOutputPort());
  largest->SetExtractionModeToLargestRegion();
  largest->Update();
  return FromPolyData(CleanTriangulate(largest->GetOutput()));
}

TriangleMesh DecimateAndSmooth(const TriangleMesh& dense, const DecimateSmoothOptions& options) {
  if (options.target_vertices <= 3 || options.smoothing_iterations < 0 || !(options.passband > 0) ||
      !(options.passband < 2)) {
    throw std::invalid_argument("DecimateAndSmooth: options out of range");
  }
  auto input = ToPolyData(dense);
  auto decimate = vtkSmartPointer<vtkQuadricDecimation>::New();
  decimate->SetInputData(input);
  const double keep = std::min(1.0, static_cast<double>(options.target_vertices) / dense.num_vertices());
  decimate->SetTargetReduction(1.0 - keep);
  decimate->VolumePreservationOn();
  decimate->AttributeErrorMetricOff();

  auto smooth = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
  smooth->SetInputConnection(decimate->GetOutputPort());
  smooth->SetNumberOfIterations(options.smoothing_iterations);
  smooth->SetPassBand(options.passband);
  smooth->NormalizeCoordinatesOn();  // pass band independent of the organ's size
  smooth->FeatureEdgeSmoothingOff();
  smooth->BoundarySmoothingOff();  // keeps clipped rims where they were cut
  smooth->NonManifoldSmoothingOn();
  smooth->Update();

  // Consistent winding across the surface; the outward sign is set later from the field.
  auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();
  normals->SetInputData(CleanTriangulate(smooth->GetOutput()));
  normals->ConsistencyOn();
  normals->AutoOrientNormalsOff();
  normals->SplittingOff();
  normals->ComputeCellNormalsOff();
  normals->Update();
  return FromPolyData(normals->GetOutput());
}

TriangleMesh ClipKeepAbove(const TriangleMesh& mesh, const Eigen::Vector3d& plane_point_m,
                           const Eigen::Vector3d& normal) {
  auto plane = vtkSmartPointer<vtkPlane>::New();
  plane->SetOrigin(plane_point_m.data());
  plane->SetNormal(normal.data());
  auto clip = vtkSmartPointer<vtkClipPolyData>::New();
  clip->SetInputData(ToPolyData(mesh));
  clip->SetClipFunction(plane);
  clip->InsideOutOff();  // keeps where the plane function is positive
  clip->Update();
  return FromPolyData(CleanTriangulate(clip->GetOutput()));
}

void OrientOutward(TriangleMesh& mesh, const ImplicitField& field) {
  double agreement = 0;
  constexpr double kStep = 1e-4;  // metres, for the central-difference gradient
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    const Eigen::Vector3d centre = (a + b + c) / 3;
    Eigen::Vector3d gradient;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d h = Eigen::Vector3d::Zero();
      h[k] = kStep;
      gradient[k] = field(centre + h) - field(centre - h);
    }
    agreement += (b - a).cross(c - a).dot(gradient.normalized());
  }
  if (agreement < 0) mesh.triangles.col(1).swap(mesh.triangles.col(2));
}

}  // namespace vesica::app::anatomy
