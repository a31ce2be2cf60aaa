// Calot's triangle drawn (issue 36): each structure where it projects, in its colour; a clip
// across a tube; the fat layer as one surface that hides what it covers, opens where cells are
// removed and moves with its cells; a cut's gap; a bleeding end. Pixels are
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
#include <cmath>
#include <stdexcept>
#include <vector>

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
  const CalotActors& actors() const { return actors_; }

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

const Eigen::Vector3d kDuctA(-0.02, 0, 0.01), kDuctB(0.02, 0, 0.01);        // horizontal, upper
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
  EXPECT_TRUE(Black(view.At(Eigen::Vector3d(0, 0, 0))));         // between them: nothing
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

// A patch of the layer in front of the duct's middle (toward the camera, +y): 7 cells along the
// duct, 3 deep, 5 across, 4 to 8 mm in front of its axis.
std::vector<Eigen::Vector3d> FatPatch(double remove_within_x_m = -1) {
  std::vector<Eigen::Vector3d> cells;
  for (int i = -3; i <= 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = -2; k <= 2; ++k)
        if (std::abs(0.002 * i) > remove_within_x_m) cells.emplace_back(0.002 * i, 0.004 + 0.002 * j, 0.01 + 0.002 * k);
  return cells;
}

bool Fat(Pixel p) { return p.r > p.b + 40 && p.r > p.g + 5; }

TEST(CalotActors, FatHidesTheStructureItCoversUntilItIsRemoved) {
  CalotView& view = CalotView::Shared();
  CalotDrawing d = TwoStructures();
  d.fat_cells_W = FatPatch();
  view.Draw(d);
  const Pixel covered = view.At(Eigen::Vector3d(0, 0, 0.01));
  EXPECT_TRUE(Fat(covered)) << covered.r << " " << covered.g << " " << covered.b;  // yellow fat
  EXPECT_TRUE(Greenish(view.At(Eigen::Vector3d(-0.015, 0, 0.01))));                // uncovered part
  // One continuous layer: fat between neighbouring cells' centres too, not beads on black.
  for (double x = -0.006; x <= 0.006; x += 0.0005) {
    const Pixel between = view.At(Eigen::Vector3d(x, 0.004, 0.013));
    EXPECT_TRUE(Fat(between)) << x << ": " << between.r << " " << between.g << " " << between.b;
  }
  // Burnt through where the cells within 2 mm of the middle went (all three deep): a hole
  // through which the duct shows, the fat either side still there.
  d.fat_cells_W = FatPatch(0.0021);
  view.Draw(d);
  const Pixel hole = view.At(Eigen::Vector3d(0, 0, 0.01));
  EXPECT_TRUE(Greenish(hole)) << hole.r << " " << hole.g << " " << hole.b;
  EXPECT_TRUE(Fat(view.At(Eigen::Vector3d(-0.005, 0, 0.01))));
  EXPECT_TRUE(Fat(view.At(Eigen::Vector3d(0.005, 0, 0.01))));
  d.fat_cells_W.clear();  // all burnt away
  view.Draw(d);
  EXPECT_TRUE(Greenish(view.At(Eigen::Vector3d(0, 0, 0.01))));
}

// The layer's surface is rebuilt when the set of intact cells changes, not when they move: then
// it moves with them (the cells' rest places stay the lattice).
TEST(CalotActors, TheFatLayerIsRebuiltOnlyWhenItsCellsChangeAndMovesWithThem) {
  CalotView& view = CalotView::Shared();
  CalotDrawing d = TwoStructures();
  d.fat_cells_W = FatPatch();
  view.Draw(d);
  const int rebuilds = view.actors().fat().rebuilds();
  const Eigen::Vector3d beside(0.0105, 0, 0.01);  // on the duct, 4.5 mm past the patch's last cells
  EXPECT_TRUE(Greenish(view.At(beside)));
  view.Draw(d);
  EXPECT_EQ(view.actors().fat().rebuilds(), rebuilds);
  d.fat_cells_rest_W = d.fat_cells_W;
  for (Eigen::Vector3d& p : d.fat_cells_W) p.x() += 0.004;  // pushed 4 mm along the duct
  view.Draw(d);
  EXPECT_EQ(view.actors().fat().rebuilds(), rebuilds);
  EXPECT_TRUE(Fat(view.At(beside)));
  EXPECT_TRUE(Greenish(view.At(Eigen::Vector3d(-0.0085, 0, 0.01))));  // uncovered behind it
  d.fat_cells_W.pop_back();
  d.fat_cells_rest_W.pop_back();
  view.Draw(d);
  EXPECT_EQ(view.actors().fat().rebuilds(), rebuilds + 1);
}

TEST(CalotActors, MismatchedFatRestPlacesAreRefused) {
  CalotActors actors;
  CalotDrawing d;
  d.fat_cells_W = FatPatch();
  d.fat_cells_rest_W = {Eigen::Vector3d::Zero()};
  EXPECT_THROW(actors.Update(d), std::invalid_argument);
  d.fat_cells_rest_W.clear();
  d.fat_cell_size_m = 0;
  EXPECT_THROW(actors.Update(d), std::invalid_argument);
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
