// One gallbladder triangle that Mesa's llvmpipe (Debian 12, Mesa 22.3.6) never finished drawing
// with a mipmapped texture: at 400 x 225 it projects to a sliver a third of a pixel wide, and the
// draw spun forever inside llvmpipe's generated sampling code. It froze the soak (issue 31) and
// `vesica-replay --png-dir` at 17.895 s of the committed dissection. The organs' texture is now
// sampled without mipmaps; this test draws that triangle, as it was on screen, with the organs'
// texture. Before the fix it never returned (CTest's timeout is the failure).

#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include "app/render/tissue_texture.h"

namespace vesica::app {
namespace {

template <class T>
using Ptr = vtkSmartPointer<T>;

struct Corner {
  double xyz[3];
  float uv[2];
  float normal[3];
};

// Display-frame corners, texture coordinates and normals of the gallbladder's triangle 268 in the
// frame at 17.895 s, to the bit (dumped from the view).
constexpr Corner kSliver[3] = {
    {{0.030626205649750212, 0.006629120318340478, 0.028188016459054048},
     {0.2093999981880188f, 1.3402999639511108f},
     {-0.9682306051254272f, 0.15257269144058228f, 0.19811883568763733f}},
    {{0.03014890061930339, 0.002655687620309542, 0.0280485362432506},
     {0.014949999749660492f, 1.3305000066757202f},
     {-0.9810738563537598f, 0.0810796245932579f, 0.17584145069122314f}},
    {{0.031015178189229255, 0.003237443695868914, 0.030813419331829323},
     {0.03985000029206276f, 1.468999981880188f},
     {-0.909093976020813f, 0.05166864022612572f, 0.41337448358535767f}},
};

// The gallbladder's bounds at that moment. VTK uploads the points shifted and scaled by their
// array's range, so the floats llvmpipe saw depend on them: two unused points keep that range.
constexpr double kGallbladderMin[3] = {0.0167963546119046, -0.02257515840333005, -0.006372596612669852};
constexpr double kGallbladderMax[3] = {0.06072597753732651, 0.06022686092221407, 0.03837527061061104};

Ptr<vtkPolyData> SliverPolyData() {
  auto points = Ptr<vtkPoints>::New();
  points->SetDataTypeToDouble();
  auto uv = Ptr<vtkFloatArray>::New();
  uv->SetNumberOfComponents(2);
  auto normals = Ptr<vtkFloatArray>::New();
  normals->SetNumberOfComponents(3);
  for (const Corner& c : kSliver) {
    points->InsertNextPoint(c.xyz);
    uv->InsertNextTypedTuple(c.uv);
    normals->InsertNextTypedTuple(c.normal);
  }
  for (const double* corner : {kGallbladderMin, kGallbladderMax}) {
    constexpr float kUnusedUv[2] = {0, 0}, kUnusedNormal[3] = {0, 0, 1};
    points->InsertNextPoint(corner);
    uv->InsertNextTypedTuple(kUnusedUv);
    normals->InsertNextTypedTuple(kUnusedNormal);
  }
  auto cells = Ptr<vtkCellArray>::New();
  const vtkIdType ids[3] = {0, 1, 2};
  cells->InsertNextCell(3, ids);
  auto poly = Ptr<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  poly->GetPointData()->SetTCoords(uv);
  poly->GetPointData()->SetNormals(normals);
  return poly;
}

TEST(SliverRenderTest, TheTriangleThatFrozeLlvmpipeIsDrawn) {
  auto mapper = Ptr<vtkPolyDataMapper>::New();
  mapper->SetInputData(SliverPolyData());
  auto actor = Ptr<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetTexture(MakeTissueTexture(256, 7));  // the organs' texture, as the view makes it

  auto renderer = Ptr<vtkRenderer>::New();
  renderer->SetBackground(0, 0, 0);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.0099065139675768611, 0.091458589171129007, -0.07045963246033278);
  camera->SetFocalPoint(0.040638000000000001, 0.013643000000000001, 0.021179);
  camera->SetViewUp(0.19939124014729664, 0.77893049006651593, 0.59456742678796359);
  camera->SetViewAngle(60);
  camera->SetClippingRange(0.0070395686605221894, 0.70395686605221897);

  auto window = Ptr<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->SetSize(400, 225);
  window->Render();  // never returned before the fix

  // The sliver is drawn: lit pixels near (217, 105) (column 217, rows 102-108 from
  // the bottom, as projected by the camera), and nothing far from it.
  auto grab = Ptr<vtkWindowToImageFilter>::New();
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkImageData* image = grab->GetOutput();
  int lit_near = 0, lit_far = 0;
  for (int row = 0; row < 225; ++row)
    for (int col = 0; col < 400; ++col) {
      const auto* px = static_cast<unsigned char*>(image->GetScalarPointer(col, row, 0));
      const bool lit = px[0] + px[1] + px[2] > 30;
      const bool near = col >= 214 && col <= 221 && row >= 99 && row <= 111;
      (near ? lit_near : lit_far) += lit ? 1 : 0;
    }
  EXPECT_GE(lit_near, 1);  // a third of a pixel wide: it covers one pixel centre or two
  EXPECT_EQ(lit_far, 0);
}

}  // namespace
}  // namespace vesica::app
