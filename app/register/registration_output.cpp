#include "app/register/registration_output.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace vesica::app::registration {

namespace {
std::string FrameFileName(int frame) {
  char name[64];
  std::snprintf(name, sizeof name, "registered_%04d.vtu", frame);
  return name;
}

void WriteFrameVtu(const std::filesystem::path& file, const physics::TetrahedralMesh& rest,
                   const physics::Vertices& x) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> displacement;
  displacement->SetName("displacement_m");
  displacement->SetNumberOfComponents(3);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    points->InsertNextPoint(x(i, 0), x(i, 1), x(i, 2));
    const Eigen::RowVector3d u = x.row(i) - rest.vertices.row(i);
    displacement->InsertNextTuple3(u[0], u[1], u[2]);
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->Allocate(rest.num_tets());
  for (int t = 0; t < rest.num_tets(); ++t) {
    const vtkIdType ids[4] = {rest.tets(t, 0), rest.tets(t, 1), rest.tets(t, 2), rest.tets(t, 3)};
    grid->InsertNextCell(VTK_TETRA, 4, ids);
  }
  grid->GetPointData()->AddArray(displacement);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(file.string().c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToBinary();
  if (writer->Write() != 1) throw std::runtime_error(file.string() + ": cannot be written");
}

std::ofstream OpenText(const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error(file.string() + ": cannot be written");
  out.precision(9);
  return out;
}
}  // namespace

void WriteRegistrationOutputs(const std::filesystem::path& dir, const physics::TetrahedralMesh& rest,
                              const std::vector<RegisteredFrame>& frames) {
  std::ofstream pvd = OpenText(dir / "registered.pvd");
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  std::ofstream displacement = OpenText(dir / "displacement.csv");
  displacement << "frame,time_s,node,ux_m,uy_m,uz_m\n";
  std::ofstream residuals = OpenText(dir / "residuals.csv");
  residuals << "frame,time_s,points,paired,mean_gap_m,max_gap_m,constraint_iterations,fem_iterations\n";
  for (const RegisteredFrame& f : frames) {
    const std::string name = FrameFileName(f.frame);
    WriteFrameVtu(dir / name, rest, f.positions_W);
    pvd << "    <DataSet timestep=\"" << f.time_s << "\" part=\"0\" file=\"" << name << "\"/>\n";
    for (Eigen::Index i = 0; i < f.positions_W.rows(); ++i) {
      const Eigen::RowVector3d u = f.positions_W.row(i) - rest.vertices.row(i);
      displacement << f.frame << ',' << f.time_s << ',' << i << ',' << u[0] << ',' << u[1] << ',' << u[2] << '\n';
    }
    const physics::RegistrationStepReport& r = f.last_step;
    residuals << f.frame << ',' << f.time_s << ',' << f.points << ',' << r.paired_points << ',' << r.mean_gap_after_m
              << ',' << r.max_gap_after_m << ',' << r.constraints.iterations << ',' << r.fem.solver_iterations << '\n';
  }
  pvd << "  </Collection>\n</VTKFile>\n";
  for (std::ofstream* out : {&pvd, &displacement, &residuals})
    if (!out->flush()) throw std::runtime_error(dir.string() + ": an output file could not be written");
}

}  // namespace vesica::app::registration
