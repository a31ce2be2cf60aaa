// Calot's triangle drawn (issue 36): each structure where it projects, in its colour; a clip
// across a tube; the fat layer hiding what it covers; a cut's gap; a bleeding end. Pixels are
// checked at independent projections of the drawing's own points through the camera.
#include "app/render/calot_actors.h"

#include <gtest/gtest.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <array>

#include "app/render/display_frame.h"

namespace vesica::app {
namespace {

using physics::calot::TubeKind;

struct Pixel {
  int r = 0, g = 0, b = 0;
};

// One window for the whole suite, as the trainer keeps its window: a fresh X connection per test
// sometimes failed ("bad X server connection") when the Xvfb tests ran in parallel.
class CalotView {
 public:
  static CalotView& Shared() {
    static CalotView* view = new CalotView;  // kept to the end: no GL teardown after main returns
    return *view;
  }
  CalotView() {
    window_->SetOffScreenRendering(1);
    window_->SetMultiSamples(0);
    window_->SetSize(kW, kH);
    window_->AddRenderer(renderer_);
    renderer_->SetBackground(0, 0, 0);
    for (vtkActor* a : actors_.actors()) renderer_->AddActor(a);
    // Looking down -y (anterior to posterior) at the origin, cranial (+z) up, 6 cm across.
    vtkCamera* camera = renderer_->GetActiveCamera();
    camera->SetPosition(0, 0.1, 0);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(33.4);
    renderer_->ResetCameraClippingRange(-0.05, 0.05, -0.05, 0.05, -0.05, 0.05);
  }
  void Draw(const CalotDrawing& d) {
    actors_.Update(d);
    renderer_->ResetCameraClippingRange(-0.05, 0.05, -0.05, 0.05, -0.05, 0.05);
    window_->Render();
    auto grab = vtkSmartPointer<vtkWindowToImageFilter>::New();
    grab->SetInput(window_);
    grab->ReadFrontBufferOff();
    grab->SetInputBufferTypeToRGB();
    grab->Update();
    image_ = grab->GetOutput();
  }
  /// The pixel where the patient-frame point projects (an independent projection: the camera's
  /// own world-to-display transform of the mirrored point).
  Pixel At(const Eigen::Vector3d& p_W) {
    const Eigen::Vector3d d = ToDisplay(p_W);
    renderer_->SetWorldPoint(d.x(), d.y(), d.z(), 1.0);
    renderer_->WorldToDisplay();
    const double* px = renderer_->GetDisplayPoint();
    const auto* c = static_cast<const unsigned char*>(
        image_->GetScalarPointer(static_cast<int>(px[0] + 0.5), static_cast<int>(px[1] + 0.5), 0));
    return {c[0], c[1], c[2]};
  }

 private:
  static constexpr int kW = 640, kH = 480;
  vtkSmartPointer<vtkRenderWindow> window_ = vtkSmartPointer<vtkRenderWindow>::New();
  vtkSmartPointer<vtkRenderer> renderer_ = vtkSmartPointer<vtkRenderer>::New();
  CalotActors actors_;
  vtkSmartPointer<vtkImageData> image_;
};

CalotTubeDrawing Straight(TubeKind kind, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius) {
  CalotTubeDrawing t;
  t.kind = kind;
  for (int i = 0; i <= 10; ++i) t.centreline_W.push_back(a + (b - a) * (i / 10.0));
  t.radius_m = radius;
  return t;
}

const Eigen::Vector3d kDuctA(-0.02, 0, 0.01), kDuctB(0.02, 0, 0.01);     // horizontal, upper
const Eigen::Vector3d kArteryA(-0.02, 0, -0.01), kArteryB(0.02, 0, -0.01);  // horizontal, lower

CalotDrawing TwoStructures() {
  CalotDrawing d;
  d.tubes.push_back(Straight(TubeKind::kCysticDuct, kDuctA, kDuctB, 0.0015));
  d.tubes.push_back(Straight(TubeKind::kCysticArtery, kArteryA, kArteryB, 0.001));
  return d;
}

bool Greenish(Pixel p) { return p.g >= p.r && p.g > p.b + 20 && p.g > 40; }
bool Red(Pixel p) { return p.r > 2 * p.g && p.r > 2 * p.b && p.r > 40; }
bool Black(Pixel p) { return p.r + p.g + p.b < 10; }

TEST(CalotActors, EachStructureIsDrawnWhereItLiesInItsColour) {
  CalotView& view = CalotView::Shared();
  view.Draw(TwoStructures());
  const Pixel duct = view.At(0.5 * (kDuctA + kDuctB));
  const Pixel artery = view.At(0.5 * (kArteryA + kArteryB));
  EXPECT_TRUE(Greenish(duct)) << duct.r << " " << duct.g << " " << duct.b;
  EXPECT_TRUE(Red(artery)) << artery.r << " " << artery.g << " " << artery.b;
  EXPECT_TRUE(Black(view.At(Eigen::Vector3d(0, 0, 0))));  // between them: nothing
  EXPECT_TRUE(Black(view.At(Eigen::Vector3d(0.025, 0, 0.01))));  // past the duct's end
}

TEST(CalotActors, AClipIsATitaniumBarAcrossItsTube) {
  CalotView& view = CalotView::Shared();
  CalotDrawing d = TwoStructures();
  const Eigen::Vector3d at(0.005, 0, 0.01);
  d.clips.push_back({at, (kDuctB - kDuctA).normalized(), 0.0015});
  view.Draw(d);
  const Pixel clip = view.At(at);
  EXPECT_LT(std::abs(clip.r - clip.b), 40) << clip.r << " " << clip.g << " " << clip.b;  // grey metal
  EXPECT_GT(clip.r + clip.g + clip.b, 150);
  const Pixel beyond = view.At(at + Eigen::Vector3d(0, 0, 0.0025));  // 2.5 mm off the duct: the bar
  EXPECT_FALSE(Black(beyond));
  EXPECT_TRUE(Greenish(view.At(Eigen::Vector3d(-0.01, 0, 0.01))));  // the duct away from the clip
}

TEST(CalotActors, FatHidesTheStructureItCoversUntilItIsRemoved) {
  CalotView& view = CalotView::Shared();
  CalotDrawing d = TwoStructures();
  for (int i = -2; i <= 2; ++i)  // a lobule row in front of the duct's middle (toward the camera, +y)
    d.fat_cells_W.push_back(Eigen::Vector3d(0.002 * i, 0.003, 0.01));
  view.Draw(d);
  const Pixel covered = view.At(Eigen::Vector3d(0, 0, 0.01));
  EXPECT_GT(covered.r, covered.b + 40) << covered.r << " " << covered.g << " " << covered.b;  // yellow fat
  EXPECT_GT(covered.r, covered.g - 10);
  EXPECT_TRUE(Greenish(view.At(Eigen::Vector3d(-0.015, 0, 0.01))));  // uncovered part
  d.fat_cells_W.clear();                                            // burnt away
  view.Draw(d);
  EXPECT_TRUE(Greenish(view.At(Eigen::Vector3d(0, 0, 0.01))));
}

TEST(CalotActors, ACutLeavesAGapAndABleedingEndShowsBlood) {
  CalotView& view = CalotView::Shared();
  CalotDrawing d;
  d.tubes.push_back(Straight(TubeKind::kCysticArtery, kArteryA, Eigen::Vector3d(-0.003, 0, -0.01), 0.001));
  d.tubes.push_back(Straight(TubeKind::kCysticArtery, Eigen::Vector3d(0.003, 0, -0.01), kArteryB, 0.001));
  view.Draw(d);
  EXPECT_TRUE(Black(view.At(Eigen::Vector3d(0, 0, -0.01))));  // the gap between the stumps
  EXPECT_TRUE(Red(view.At(Eigen::Vector3d(-0.01, 0, -0.01))));
  d.leaks.push_back({Eigen::Vector3d(-0.003, 0, -0.01), true});
  view.Draw(d);
  const Pixel pool = view.At(Eigen::Vector3d(-0.003, 0, -0.012));  // 2 mm below the end, inside the pool
  EXPECT_TRUE(Red(pool)) << pool.r << " " << pool.g << " " << pool.b;
}

}  // namespace
}  // namespace vesica::app
