#include "app/patient/patient_meshing.h"

#include <vtkCellArray.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkQuadricDecimation.h>
#include <vtkTriangleFilter.h>
#include <vtkTypeUInt8Array.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <Eigen/LU>
#include <array>
#include <stdexcept>

#include "physics/patient/patient_labels.h"

namespace vesica::app::patient {
namespace label = physics::patient_label;

physics::TriangleMesh MeshLabels(const physics::LabelVolume& volume, const std::vector<std::uint8_t>& labels,
                                 const std::string& organ, const MeshingOptions& options) {
  std::array<bool, 256> in{};
  for (std::uint8_t l : labels) in[l] = true;
  // A one-voxel empty border so that the surface closes where the organ meets the volume's edge.
  const int nx = volume.dims[0] + 2, ny = volume.dims[1] + 2, nz = volume.dims[2] + 2;
  vtkNew<vtkTypeUInt8Array> mask;
  mask->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  mask->FillValue(0);
  std::uint8_t* m = mask->GetPointer(0);
  bool any = false;
  for (int k = 0; k < volume.dims[2]; ++k)
    for (int j = 0; j < volume.dims[1]; ++j)
      for (int i = 0; i < volume.dims[0]; ++i)
        if (in[volume.At(i, j, k)]) {
          m[(i + 1) + static_cast<std::size_t>(nx) * ((j + 1) + static_cast<std::size_t>(ny) * (k + 1))] = 1;
          any = true;
        }
  if (!any) throw std::invalid_argument("meshing: the label map has no " + organ);
  vtkNew<vtkImageData> image;
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(volume.spacing_m.x(), volume.spacing_m.y(), volume.spacing_m.z());
  image->SetOrigin(-volume.spacing_m.x(), -volume.spacing_m.y(), -volume.spacing_m.z());
  image->GetPointData()->SetScalars(mask);

  vtkNew<vtkDiscreteFlyingEdges3D> cubes;  // (i) marching cubes on the label boundary
  cubes->SetInputData(image);
  cubes->SetValue(0, 1.0);
  cubes->ComputeNormalsOff();
  cubes->ComputeGradientsOff();
  cubes->ComputeScalarsOff();
  // The seed decimates, then smooths; smoothing the decimated mesh moved thin parts (the liver by
  // the crura) up to 6 mm off the labels, so we smooth the fine marching-cubes mesh first.
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;  // (iii) smoothing, without shrinking
  smooth->SetInputConnection(cubes->GetOutputPort());
  smooth->SetNumberOfIterations(options.smoothing_iterations);
  smooth->SetPassBand(options.smoothing_passband);
  smooth->NormalizeCoordinatesOn();
  smooth->BoundarySmoothingOff();
  smooth->FeatureEdgeSmoothingOff();
  vtkNew<vtkQuadricDecimation> decimate;  // (ii) decimation by quadric error, volume kept
  decimate->SetInputConnection(smooth->GetOutputPort());
  decimate->SetTargetReduction(options.decimate_fraction);
  decimate->VolumePreservationOn();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(decimate->GetOutputPort());
  triangles->Update();
  vtkPolyData* poly = triangles->GetOutput();

  physics::TriangleMesh mesh;
  mesh.vertices.resize(poly->GetNumberOfPoints(), 3);
  for (vtkIdType p = 0; p < poly->GetNumberOfPoints(); ++p) {
    double q[3];
    poly->GetPoint(p, q);
    const Eigen::Vector3d world = volume.origin_m + volume.direction * Eigen::Vector3d(q[0], q[1], q[2]);
    mesh.vertices.row(p) = world.transpose();
  }
  const bool flip = volume.direction.determinant() < 0.0;  // keep outward normals in the world
  mesh.triangles.resize(poly->GetNumberOfPolys(), 3);
  vtkCellArray* polys = poly->GetPolys();
  polys->InitTraversal();
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  for (vtkIdType f = 0; polys->GetNextCell(count, ids); ++f)
    mesh.triangles.row(f) << static_cast<int>(ids[0]), static_cast<int>(ids[flip ? 2 : 1]), static_cast<int>(ids[flip ? 1 : 2]);
  return mesh;
}

std::vector<OrganSurface> MeshPatient(const physics::LabelVolume& volume, const MeshingOptions& options) {
  std::array<bool, 256> present{};
  for (std::uint8_t l : volume.labels) present[l] = true;
  std::vector<OrganSurface> organs = {
      {"skin", {}, {}},
      {"lung", {label::kLung, label::kCostophrenicRecess}, {}},
      {"diaphragm", {label::kDiaphragmMuscle, label::kDiaphragmTendon}, {}},
      {"liver", {label::kLiver, label::kLiverCapsule, label::kTumour}, {}},
      {"tumour", {label::kTumour}, {}},
      {"gallbladder", {label::kGallbladder}, {}},
      {"colon", {label::kColon}, {}},
      {"spine", {label::kSpine}, {}},
      {"sternum", {label::kSternum}, {}},
  };
  for (int l = 1; l < 256; ++l)  // the skin encloses the whole body
    organs[0].labels.push_back(static_cast<std::uint8_t>(l));
  for (int side = 0; side < 2; ++side)
    for (int n = 1; n <= label::kMaxRib; ++n)
      organs.push_back({std::string("rib_") + (side ? "l" : "r") + std::to_string(n),
                        {label::Rib(side == 1, n), label::Cartilage(side == 1, n)}, {}});
  std::vector<OrganSurface> out;
  for (OrganSurface& organ : organs) {
    bool here = false;
    for (std::uint8_t l : organ.labels) here = here || present[l];
    if (!here) continue;
    organ.mesh = MeshLabels(volume, organ.labels, organ.organ, options);
    out.push_back(std::move(organ));
  }
  return out;
}

}  // namespace vesica::app::patient
