#include "app/render/smoke_sprites.h"

#include <vtkActor.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkPointGaussianMapper.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>

#include "app/render/burn_colours.h"
#include "app/render/display_frame.h"
#include "app/render/render_colours.h"

namespace vesica::app {

namespace {

// Fragment code for one splat: offsetVCVSOutput runs over the unit disc (scale = radius).
// A soft puff: opacity falls smoothly from the centre to 0 at the rim, nothing outside it.
constexpr const char* kPuffShader =
    "//VTK::Color::Impl\n"
    "float dist2 = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);\n"
    "if (dist2 > 1.0) { discard; }\n"
    "float falloff = 1.0 - dist2;\n"
    "opacity = opacity * falloff * falloff;\n";

}  // namespace

SmokeSprites::SmokeSprites() {
  poly_ = vtkSmartPointer<vtkPolyData>::New();
  auto mapper = vtkSmartPointer<vtkPointGaussianMapper>::New();
  mapper->SetInputData(poly_);
  mapper->SetScaleArray("radius");
  mapper->SetScaleFactor(1.0);
  mapper->SetSplatShaderCode(kPuffShader);
  mapper->SetTriangleScale(1.0);  // the quad just holds the unit disc
  mapper->EmissiveOff();          // alpha-blended over the scene, not added like light
  mapper->SetScalarModeToUsePointData();
  mapper->SetColorModeToDirectScalars();
  actor_ = vtkSmartPointer<vtkActor>::New();
  actor_->SetMapper(mapper);
  actor_->ForceTranslucentOn();
  actor_->GetProperty()->SetAmbient(1.0);  // smoke scatters the light: unshaded
  actor_->GetProperty()->SetDiffuse(0.0);
  actor_->VisibilityOff();
}

void SmokeSprites::Update(const std::vector<SmokeSprite>& smoke) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  auto radius = vtkSmartPointer<vtkFloatArray>::New();
  radius->SetName("radius");
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("colour");
  colours->SetNumberOfComponents(4);
  for (const auto& s : smoke) {
    const auto alpha = static_cast<unsigned char>(std::lround(255.0 * Unit(static_cast<float>(s.alpha))));
    if (alpha == 0 || s.size_m <= 0) continue;
    points->InsertNextPoint(ToDisplay(s.p_W).data());
    radius->InsertNextValue(static_cast<float>(0.5 * s.size_m));
    const unsigned char rgba[4] = {static_cast<unsigned char>(std::lround(255 * kSmokeRgb[0])),
                                   static_cast<unsigned char>(std::lround(255 * kSmokeRgb[1])),
                                   static_cast<unsigned char>(std::lround(255 * kSmokeRgb[2])), alpha};
    colours->InsertNextTypedTuple(rgba);
  }
  poly_->Initialize();
  poly_->SetPoints(points);
  poly_->GetPointData()->AddArray(radius);
  poly_->GetPointData()->SetScalars(colours);
  poly_->Modified();
  actor_->SetVisibility(points->GetNumberOfPoints() > 0);
}

}  // namespace vesica::app
