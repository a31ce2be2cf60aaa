#include "app/mesh_io/mesh_io.h"

#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkOBJWriter.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkTetra.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string>

#include "app/mesh_io/obj_geometry.h"
#include "app/mesh_io/vtk_reader_errors.h"
#include "physics/mesh/organ_scale.h"

namespace vesica::app {

namespace {

using physics::MeshError;
namespace fs = std::filesystem;

std::string Extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void RequireReadable(const fs::path& path) {
  std::error_code ec;
  // A directory opens as a stream on Linux: say what it is rather than what VTK makes of it.
  if (fs::is_directory(path, ec)) throw MeshError(path.string() + ": is a directory, not a mesh file");
  std::ifstream probe(path);
  if (!probe) throw MeshError(path.string() + ": cannot open file for reading");
}

[[noreturn]] void UnsupportedExtension(const fs::path& path, const std::string& allowed) {
  throw MeshError(path.string() + ": unsupported mesh format '" + Extension(path) + "' (expected " + allowed + ")");
}

template <typename Reader>
vtkSmartPointer<vtkPolyData> ReadPoly(const fs::path& path) {
  auto reader = vtkSmartPointer<Reader>::New();
  const VtkReaderErrors errors(reader);
  reader->SetFileName(path.string().c_str());
  reader->Update();
  errors.ThrowIfAny(path);
  return reader->GetOutput();
}

vtkSmartPointer<vtkPolyData> ReadAnyPoly(const fs::path& path) {
  const std::string ext = Extension(path);
  if (ext == ".obj") return ReadObjGeometry(path);
  if (ext == ".stl") return ReadPoly<vtkSTLReader>(path);
  if (ext == ".ply") return ReadPoly<vtkPLYReader>(path);
  if (ext == ".vtp") return ReadPoly<vtkXMLPolyDataReader>(path);
  if (ext == ".vtk") {
    auto reader = vtkSmartPointer<vtkPolyDataReader>::New();
    reader->SetFileName(path.string().c_str());
    if (!reader->IsFilePolyData()) {
      // A legacy unstructured grid: take its outer surface.
      auto grid = vtkSmartPointer<vtkUnstructuredGridReader>::New();
      const VtkReaderErrors grid_errors(grid);
      grid->SetFileName(path.string().c_str());
      auto surface = vtkSmartPointer<vtkDataSetSurfaceFilter>::New();
      surface->SetInputConnection(grid->GetOutputPort());
      surface->Update();
      grid_errors.ThrowIfAny(path);
      return surface->GetOutput();
    }
    const VtkReaderErrors errors(reader);
    reader->Update();
    errors.ThrowIfAny(path);
    return reader->GetOutput();
  }
  UnsupportedExtension(path, ".obj, .stl, .ply, .vtp or .vtk");
}

vtkSmartPointer<vtkUnstructuredGrid> ReadGrid(const fs::path& path) {
  const std::string ext = Extension(path);
  if (ext == ".vtu") {
    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    const VtkReaderErrors errors(reader);
    reader->SetFileName(path.string().c_str());
    reader->Update();
    errors.ThrowIfAny(path);
    return reader->GetOutput();
  }
  if (ext == ".vtk") {
    auto reader = vtkSmartPointer<vtkUnstructuredGridReader>::New();
    reader->SetFileName(path.string().c_str());
    if (!reader->IsFileUnstructuredGrid()) throw MeshError(path.string() + ": not a legacy VTK unstructured grid");
    const VtkReaderErrors errors(reader);
    reader->Update();
    errors.ThrowIfAny(path);
    return reader->GetOutput();
  }
  UnsupportedExtension(path, ".vtu or .vtk");
}

physics::Vertices CopyPoints(vtkPoints* points) {
  physics::Vertices v(points ? points->GetNumberOfPoints() : 0, 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    double p[3];
    points->GetPoint(i, p);
    v.row(i) << p[0], p[1], p[2];
  }
  return v;
}

vtkSmartPointer<vtkPoints> MakePoints(const physics::Vertices& v) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(v.rows());
  for (Eigen::Index i = 0; i < v.rows(); ++i) points->SetPoint(i, v(i, 0), v(i, 1), v(i, 2));
  return points;
}

// A raw index as VTK stores it; kept wide so that garbage indices are reported, not wrapped.
int CheckedIndex(vtkIdType id, const fs::path& path, const char* element, vtkIdType cell) {
  if (id < 0 || id > std::numeric_limits<int>::max())
    throw MeshError(path.string() + ": " + element + " " + std::to_string(cell) + ": vertex index " +
                    std::to_string(id) + " out of range");
  return static_cast<int>(id);
}

}  // namespace

physics::TriangleMesh ReadTriangleMesh(const fs::path& path, physics::SurfaceRequirement requirement) {
  RequireReadable(path);
  const auto poly = ReadAnyPoly(path);
  if (!poly || poly->GetNumberOfPoints() == 0) throw MeshError(path.string() + ": no vertices could be read");
  physics::TriangleMesh mesh;
  mesh.vertices = CopyPoints(poly->GetPoints());
  physics::CheckOrganScale(mesh.vertices, path.string());
  vtkCellArray* polys = poly->GetPolys();
  mesh.triangles.resize(polys ? polys->GetNumberOfCells() : 0, 3);
  if (polys) {
    auto ids = vtkSmartPointer<vtkIdList>::New();
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c) {
      polys->GetCellAtId(c, ids);
      if (ids->GetNumberOfIds() != 3)
        throw MeshError(path.string() + ": polygon " + std::to_string(c) + ": has " +
                        std::to_string(ids->GetNumberOfIds()) + " corners, only triangles are supported");
      for (int k = 0; k < 3; ++k) mesh.triangles(c, k) = CheckedIndex(ids->GetId(k), path, "triangle", c);
    }
  }
  if (auto* labels = poly->GetPointData()->GetArray(kLabelArrayName)) {
    mesh.vertex_labels.resize(labels->GetNumberOfTuples());
    for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
      mesh.vertex_labels[i] = static_cast<int>(labels->GetTuple1(i));
  }
  physics::ValidateTriangleMesh(mesh, path.string(), requirement);
  return mesh;
}

physics::TetrahedralMesh ReadTetrahedralMesh(const fs::path& path) {
  RequireReadable(path);
  const auto grid = ReadGrid(path);
  if (!grid || grid->GetNumberOfPoints() == 0) throw MeshError(path.string() + ": no vertices could be read");
  physics::TetrahedralMesh mesh;
  mesh.vertices = CopyPoints(grid->GetPoints());
  physics::CheckOrganScale(mesh.vertices, path.string());
  mesh.tets.resize(grid->GetNumberOfCells(), 4);
  auto ids = vtkSmartPointer<vtkIdList>::New();
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    if (grid->GetCellType(c) != VTK_TETRA)
      throw MeshError(path.string() + ": cell " + std::to_string(c) + ": VTK cell type " +
                      std::to_string(grid->GetCellType(c)) + " is not a tetrahedron");
    grid->GetCellPoints(c, ids);
    for (int k = 0; k < 4; ++k) mesh.tets(c, k) = CheckedIndex(ids->GetId(k), path, "tetrahedron", c);
  }
  physics::ValidateTetrahedralMesh(mesh, path.string());
  physics::ValidateTetMeshBoundary(mesh, path.string());
  return mesh;
}

void WriteTriangleMesh(const physics::TriangleMesh& mesh, const fs::path& path) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(mesh.vertices));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const vtkIdType ids[3] = {mesh.triangles(f, 0), mesh.triangles(f, 1), mesh.triangles(f, 2)};
    cells->InsertNextCell(3, ids);
  }
  poly->SetPolys(cells);
  if (mesh.vertex_labels.size() == mesh.num_vertices()) {
    auto labels = vtkSmartPointer<vtkIntArray>::New();
    labels->SetName(kLabelArrayName);
    labels->SetNumberOfTuples(mesh.num_vertices());
    for (int i = 0; i < mesh.num_vertices(); ++i) labels->SetValue(i, mesh.vertex_labels[i]);
    poly->GetPointData()->AddArray(labels);
  }
  const std::string ext = Extension(path);
  int ok = 0;
  if (ext == ".vtk") {
    auto w = vtkSmartPointer<vtkPolyDataWriter>::New();
    w->SetInputData(poly);
    w->SetFileName(path.string().c_str());
    w->SetFileTypeToASCII();
    ok = w->Write();
  } else if (ext == ".vtp") {
    auto w = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    w->SetInputData(poly);
    w->SetFileName(path.string().c_str());
    ok = w->Write();
  } else if (ext == ".obj") {
    auto w = vtkSmartPointer<vtkOBJWriter>::New();
    w->SetInputData(poly);
    w->SetFileName(path.string().c_str());
    ok = w->Write();
  } else if (ext == ".stl") {
    auto w = vtkSmartPointer<vtkSTLWriter>::New();
    w->SetInputData(poly);
    w->SetFileName(path.string().c_str());
    w->SetFileTypeToBinary();
    ok = w->Write();
  } else if (ext == ".ply") {
    auto w = vtkSmartPointer<vtkPLYWriter>::New();
    w->SetInputData(poly);
    w->SetFileName(path.string().c_str());
    ok = w->Write();
  } else {
    UnsupportedExtension(path, ".vtk, .vtp, .obj, .stl or .ply");
  }
  if (!ok) throw MeshError(path.string() + ": could not write mesh");
}

void WriteTetrahedralMesh(const physics::TetrahedralMesh& mesh, const fs::path& path) {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(MakePoints(mesh.vertices));
  grid->Allocate(mesh.num_tets());
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const vtkIdType ids[4] = {mesh.tets(t, 0), mesh.tets(t, 1), mesh.tets(t, 2), mesh.tets(t, 3)};
    grid->InsertNextCell(VTK_TETRA, 4, ids);
  }
  const std::string ext = Extension(path);
  int ok = 0;
  if (ext == ".vtu") {
    auto w = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
    w->SetInputData(grid);
    w->SetFileName(path.string().c_str());
    w->SetDataModeToAscii();  // small, diffable data files
    ok = w->Write();
  } else if (ext == ".vtk") {
    auto w = vtkSmartPointer<vtkUnstructuredGridWriter>::New();
    w->SetInputData(grid);
    w->SetFileName(path.string().c_str());
    ok = w->Write();
  } else {
    UnsupportedExtension(path, ".vtu or .vtk");
  }
  if (!ok) throw MeshError(path.string() + ": could not write mesh");
}

}  // namespace vesica::app
