#include "app/patient/patient_meshing.h"

#include <vtkCellArray.h>
#include <vtkDecimatePro.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>
#include <vtkTypeUInt8Array.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <Eigen/LU>
#include <array>
#include <climits>
#include <cstdint>
#include <stdexcept>

#include "physics/patient/patient_labels.h"

namespace vesica::app::patient {
namespace label = physics::patient_label;

namespace {

struct Box {
  std::array<int, 3> lo{INT32_MAX, INT32_MAX, INT32_MAX}, hi{-1, -1, -1};
  void Add(int i, int j, int k) {
    lo = {std::min(lo[0], i), std::min(lo[1], j), std::min(lo[2], k)};
    hi = {std::max(hi[0], i), std::max(hi[1], j), std::max(hi[2], k)};
  }
  void Add(const Box& b) {
    if (b.hi[0] < 0) return;
    Add(b.lo[0], b.lo[1], b.lo[2]);
    Add(b.hi[0], b.hi[1], b.hi[2]);
  }
  [[nodiscard]] bool empty() const { return hi[0] < 0; }
};

std::array<Box, 256> LabelBoxes(const physics::LabelVolume& volume) {
  std::array<Box, 256> boxes;
  for (int k = 0; k < volume.dims[2]; ++k)
    for (int j = 0; j < volume.dims[1]; ++j)
      for (int i = 0; i < volume.dims[0]; ++i) boxes[volume.At(i, j, k)].Add(i, j, k);
  return boxes;
}

physics::TriangleMesh MeshInBox(const physics::LabelVolume& volume, const std::array<bool, 256>& in, const Box& box,
                                const MeshingOptions& options) {
  // Only the organ's bounding box, with a one-voxel empty border so that the surface closes.
  const int nx = box.hi[0] - box.lo[0] + 3, ny = box.hi[1] - box.lo[1] + 3, nz = box.hi[2] - box.lo[2] + 3;
  vtkNew<vtkTypeUInt8Array> mask;
  mask->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  mask->FillValue(0);
  std::uint8_t* m = mask->GetPointer(0);
  for (int k = box.lo[2]; k <= box.hi[2]; ++k)
    for (int j = box.lo[1]; j <= box.hi[1]; ++j)
      for (int i = box.lo[0]; i <= box.hi[0]; ++i)
        if (in[volume.At(i, j, k)])
          m[(i - box.lo[0] + 1) + static_cast<std::size_t>(nx) *
                                      ((j - box.lo[1] + 1) + static_cast<std::size_t>(ny) * (k - box.lo[2] + 1))] = 1;
  vtkNew<vtkImageData> image;
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(volume.spacing_m.x(), volume.spacing_m.y(), volume.spacing_m.z());
  image->SetOrigin((box.lo[0] - 1) * volume.spacing_m.x(), (box.lo[1] - 1) * volume.spacing_m.y(),
                   (box.lo[2] - 1) * volume.spacing_m.z());
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
  vtkNew<vtkDecimatePro> decimate;  // (ii) decimation, topology kept (faster than quadric here)
  decimate->SetInputConnection(smooth->GetOutputPort());
  decimate->SetTargetReduction(options.decimate_fraction);
  decimate->PreserveTopologyOn();
  decimate->SplittingOff();
  decimate->BoundaryVertexDeletionOff();
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
    mesh.triangles.row(f) << static_cast<int>(ids[0]), static_cast<int>(ids[flip ? 2 : 1]),
        static_cast<int>(ids[flip ? 1 : 2]);
  return mesh;
}

}  // namespace

physics::TriangleMesh MeshLabels(const physics::LabelVolume& volume, const std::vector<std::uint8_t>& labels,
                                 const std::string& organ, const MeshingOptions& options) {
  std::array<bool, 256> in{};
  for (std::uint8_t l : labels) in[l] = true;
  Box box;
  for (int k = 0; k < volume.dims[2]; ++k)
    for (int j = 0; j < volume.dims[1]; ++j)
      for (int i = 0; i < volume.dims[0]; ++i)
        if (in[volume.At(i, j, k)]) box.Add(i, j, k);
  if (box.empty()) throw std::invalid_argument("meshing: the label map has no " + organ);
  return MeshInBox(volume, in, box, options);
}

std::vector<OrganSurface> MeshPatient(const physics::LabelVolume& volume, const MeshingOptions& options) {
  const std::array<Box, 256> boxes = LabelBoxes(volume);
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
                        {label::Rib(side == 1, n), label::Cartilage(side == 1, n)},
                        {}});
  std::vector<OrganSurface> out;
  for (OrganSurface& organ : organs) {
    Box box;
    std::array<bool, 256> in{};
    for (std::uint8_t l : organ.labels) {
      box.Add(boxes[l]);
      in[l] = true;
    }
    if (box.empty()) continue;
    organ.mesh = MeshInBox(volume, in, box, options);
    out.push_back(std::move(organ));
  }
  return out;
}

}  // namespace vesica::app::patient
