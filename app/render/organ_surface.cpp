#include "app/render/organ_surface.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkShaderProperty.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "app/render/burn_colours.h"
#include "app/render/display_frame.h"
#include "app/render/vertex_normals.h"

namespace vesica::app {

namespace {

// Smooth, deterministic mottling so organs do not look like plastic: a few incommensurate waves.
double Mottle(const Eigen::Vector3d& p) {
  const double k = 180.0;  // ~3.5 cm wavelength in metres^-1
  return 0.5 * std::sin(k * p.x() + 1.3) * std::sin(0.7 * k * p.y() + 0.4) +
         0.5 * std::sin(1.9 * k * p.z() + 2.1 * std::sin(0.5 * k * p.x()));
}

}  // namespace

OrganSurface::OrganSurface(const physics::TriangleMesh& rest, const double rgb[3], double mottle_amplitude,
                           double opacity, vtkTexture* texture, double texture_tile_m)
    : rest_(rest), rgb_{rgb[0], rgb[1], rgb[2]}, texture_(texture) {
  shade_.resize(rest_.num_vertices());
  for (int v = 0; v < rest_.num_vertices(); ++v)
    shade_[v] = 1.0 + mottle_amplitude * Mottle(rest_.vertices.row(v).transpose());

  const vtkIdType n_corners = 3 * static_cast<vtkIdType>(rest_.num_triangles());
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n_corners);
  auto normals = vtkSmartPointer<vtkFloatArray>::New();
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n_corners);
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("colour");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(n_corners);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  for (vtkIdType f = 0; f < rest_.num_triangles(); ++f) {
    const vtkIdType ids[3] = {3 * f, 3 * f + 2, 3 * f + 1};  // reversed: the display frame is mirrored
    cells->InsertNextCell(3, ids);
  }
  poly_ = vtkSmartPointer<vtkPolyData>::New();
  poly_->SetPoints(points);
  poly_->SetPolys(cells);
  poly_->GetPointData()->SetNormals(normals);
  poly_->GetPointData()->SetScalars(colours);
  if (texture != nullptr) {
    auto tcoords = vtkSmartPointer<vtkFloatArray>::New();
    tcoords->SetName("TCoords");
    tcoords->SetNumberOfComponents(2);
    tcoords->SetNumberOfTuples(n_corners);
    float* uv = tcoords->GetPointer(0);
    for (int f = 0; f < rest_.num_triangles(); ++f) {
      const Eigen::Vector3d a = rest_.vertices.row(rest_.triangles(f, 0)).transpose();
      const Eigen::Vector3d b = rest_.vertices.row(rest_.triangles(f, 1)).transpose();
      const Eigen::Vector3d c = rest_.vertices.row(rest_.triangles(f, 2)).transpose();
      int axis = 0;
      (b - a).cross(c - a).cwiseAbs().maxCoeff(&axis);
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;  // the two axes of the projection plane
      for (int k = 0; k < 3; ++k) {
        const auto p = rest_.vertices.row(rest_.triangles(f, k));
        const std::size_t corner = 2 * (3 * static_cast<std::size_t>(f) + k);
        uv[corner] = static_cast<float>(p(i) / texture_tile_m);
        uv[corner + 1] = static_cast<float>(p(j) / texture_tile_m);
      }
    }
    poly_->GetPointData()->SetTCoords(tcoords);
  }
  WriteGeometry(rest_.vertices);
  burn_.assign(rest_.num_vertices(), 1.0f);  // forces the first SetBurn to write every colour
  SetBurn({});

  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(poly_);
  mapper->SetScalarModeToUsePointData();
  mapper->SetColorModeToDirectScalars();
  actor_ = vtkSmartPointer<vtkActor>::New();
  actor_->SetMapper(mapper);
  if (texture != nullptr) actor_->SetTexture(texture);
  auto* prop = actor_->GetProperty();
  prop->SetInterpolationToPhong();
  prop->SetAmbient(0.12);
  prop->SetDiffuse(0.85);
  prop->SetSpecular(0.35);  // wet serosa
  prop->SetSpecularPower(40);
  prop->SetOpacity(opacity);
}

vtkActor* OrganSurface::actor() const { return actor_; }
vtkPolyData* OrganSurface::poly_data() const { return poly_; }

void OrganSurface::WriteGeometry(const physics::Vertices& vertices) {
  const physics::Vertices normals = VertexNormals(vertices, rest_.triangles);
  auto* xyz = vtkDoubleArray::SafeDownCast(poly_->GetPoints()->GetData())->GetPointer(0);
  auto* nrm = vtkFloatArray::SafeDownCast(poly_->GetPointData()->GetNormals())->GetPointer(0);
  for (int f = 0; f < rest_.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = rest_.triangles(f, k);
      const std::size_t corner = 3 * (3 * static_cast<std::size_t>(f) + k);
      for (int c = 0; c < 3; ++c) {
        const double mirror = c == 0 ? -1.0 : 1.0;  // display frame (display_frame.h)
        xyz[corner + c] = mirror * vertices(v, c);
        nrm[corner + c] = static_cast<float>(mirror * normals(v, c));
      }
    }
  bounds_D_ = DisplayBounds{};
  for (vtkIdType corner = 0; corner < poly_->GetNumberOfPoints(); ++corner)
    bounds_D_.Extend(xyz[3 * corner], xyz[3 * corner + 1], xyz[3 * corner + 2]);
  poly_->GetPoints()->Modified();
  poly_->GetPointData()->GetNormals()->Modified();
  poly_->Modified();
}

void OrganSurface::SetVertices(const physics::Vertices& vertices) {
  if (vertices.rows() == 0) {
    if (!deformed_) return;  // already at rest: nothing to upload
    WriteGeometry(rest_.vertices);
    deformed_ = false;
    return;
  }
  WriteGeometry(vertices);
  deformed_ = true;
}

void OrganSurface::SetBurn(const std::vector<float>& burn) {
  next_burn_.assign(rest_.num_vertices(), 0.0f);
  if (!burn.empty())
    for (int f = 0; f < rest_.num_triangles(); ++f) {
      const float b = Unit(burn[static_cast<std::size_t>(f)]);
      for (int k = 0; k < 3; ++k) {
        float& v = next_burn_[static_cast<std::size_t>(rest_.triangles(f, k))];
        v = std::max(v, b);
      }
    }
  if (next_burn_ == burn_) return;
  auto* colours = vtkUnsignedCharArray::SafeDownCast(poly_->GetPointData()->GetScalars());
  auto* rgb = colours->GetPointer(0);
  for (int f = 0; f < rest_.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(rest_.triangles(f, k));
      if (next_burn_[v] == burn_[v]) continue;  // only re-colour corners whose burn changed
      const auto c = BurnedColour(rgb_, shade_[v], next_burn_[v]);
      const std::size_t corner = 3 * (3 * static_cast<std::size_t>(f) + k);
      rgb[corner] = c[0];
      rgb[corner + 1] = c[1];
      rgb[corner + 2] = c[2];
    }
  burn_.swap(next_burn_);
  colours->Modified();
  poly_->Modified();
}

void OrganSurface::UsePbr(double roughness, vtkTexture* normal_map, double normal_scale) {
  auto* prop = actor_->GetProperty();
  prop->SetInterpolationToPBR();
  prop->SetMetallic(0.0);
  prop->SetRoughness(roughness);
  prop->SetAmbient(0.0);
  prop->SetDiffuse(1.0);
  // The vertex colours are sRGB (what BurnedColour and the tests speak); PBR lights in linear
  // colour and gamma-encodes its result, so the colour is decoded in the shader, at full precision.
  actor_->GetShaderProperty()->AddFragmentShaderReplacement(
      "//VTK::Color::Impl", true, "//VTK::Color::Impl\n  diffuseColor = pow(diffuseColor, vec3(2.2));\n", false);
  if (texture_ != nullptr) {
    actor_->SetTexture(nullptr);
    texture_->UseSRGBColorSpaceOn();
    prop->SetBaseColorTexture(texture_);
  }
  if (normal_map != nullptr && poly_->GetPointData()->GetTCoords() != nullptr) {
    // Tangents of the box mapping: u runs along the rest projection plane's first axis.
    auto tangents = vtkSmartPointer<vtkFloatArray>::New();
    tangents->SetName("Tangents");
    tangents->SetNumberOfComponents(3);
    tangents->SetNumberOfTuples(3 * static_cast<vtkIdType>(rest_.num_triangles()));
    float* t = tangents->GetPointer(0);
    for (int f = 0; f < rest_.num_triangles(); ++f) {
      const Eigen::Vector3d a = rest_.vertices.row(rest_.triangles(f, 0)).transpose();
      const Eigen::Vector3d b = rest_.vertices.row(rest_.triangles(f, 1)).transpose();
      const Eigen::Vector3d c = rest_.vertices.row(rest_.triangles(f, 2)).transpose();
      int axis = 0;
      (b - a).cross(c - a).cwiseAbs().maxCoeff(&axis);
      const Eigen::Vector3d u_D = ToDisplay(Eigen::Vector3d::Unit((axis + 1) % 3));
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) t[9 * static_cast<std::size_t>(f) + 3 * k + i] = static_cast<float>(u_D(i));
    }
    poly_->GetPointData()->SetTangents(tangents);
    prop->SetNormalTexture(normal_map);
    prop->SetNormalScale(normal_scale);
  }
}

}  // namespace vesica::app
