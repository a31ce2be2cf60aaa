// Renders the default scenario the way a user would (the vesica-trainer binary, headless and as a
// window) and checks the picture: the organs must be where an independent camera model says
// they project, in their own colours. Runs under its own Xvfb (see CMakeLists.txt).

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "screen_projection.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;

struct Rgb {
  int r, g, b;
};

class Image {
 public:
  explicit Image(const fs::path& png) {
    auto reader = vtkSmartPointer<vtkPNGReader>::New();
    reader->SetFileName(png.string().c_str());
    reader->Update();
    data_ = reader->GetOutput();
    int dims[3];
    data_->GetDimensions(dims);
    width_ = dims[0];
    height_ = dims[1];
  }
  int width() const { return width_; }
  int height() const { return height_; }
  // Row 0 is the top of the picture (VTK images start at the bottom).
  Rgb at(int col, int row) const {
    const auto* p = static_cast<const unsigned char*>(data_->GetScalarPointer(col, height_ - 1 - row, 0));
    return {p[0], p[1], p[2]};
  }

 private:
  vtkSmartPointer<vtkImageData> data_;
  int width_ = 0, height_ = 0;
};

// Classifiers from the view's organ colours: liver red-brown, gallbladder green.
bool IsLiver(Rgb c) { return c.r > 40 && c.r > 1.5 * c.g && c.r > 1.5 * c.b; }
bool IsGallbladder(Rgb c) { return c.g > 40 && c.g > 1.15 * c.r && c.g > 1.3 * c.b; }

double FractionNear(const Image& img, const Eigen::Vector2d& centre, double radius, bool (*is)(Rgb)) {
  int hits = 0, total = 0;
  for (int row = 0; row < img.height(); ++row)
    for (int col = 0; col < img.width(); ++col)
      if ((Eigen::Vector2d(col, row) - centre).norm() <= radius) {
        ++total;
        hits += is(img.at(col, row));
      }
  return total ? static_cast<double>(hits) / total : 0.0;
}

double FractionOfImage(const Image& img, bool (*is)(Rgb)) {
  int hits = 0;
  for (int row = 0; row < img.height(); ++row)
    for (int col = 0; col < img.width(); ++col) hits += is(img.at(col, row));
  return static_cast<double>(hits) / (img.width() * img.height());
}

// The centre of the organ's visible part: the mean of its vertices facing the laparoscope.
Eigen::Vector3d FacingCentroid(const physics::TriangleMesh& mesh, const Eigen::Vector3d& eye) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Eigen::Vector3d c = (mesh.vertices.row(mesh.triangles(f, 0)) + mesh.vertices.row(mesh.triangles(f, 1)) +
                               mesh.vertices.row(mesh.triangles(f, 2))).transpose() / 3.0;
    if (physics::TriangleNormal(mesh, f).dot(eye - c) > 0) {
      sum += c;
      ++n;
    }
  }
  return sum / n;
}

void ExpectOrgansInPicture(const fs::path& png, const Scenario& s, const SceneMeshes& m) {
  ASSERT_TRUE(fs::exists(png)) << png;
  const Image img(png);
  ASSERT_GT(img.width(), 0);
  const double radius = 0.04 * img.height();
  const auto eye = s.laparoscope.position_m;
  const Eigen::Vector2d liver_px =
      testing::ProjectToPixel(s.laparoscope, FacingCentroid(m.liver, eye), img.width(), img.height());
  const Eigen::Vector2d gb_px =
      testing::ProjectToPixel(s.laparoscope, FacingCentroid(m.gallbladder_surface, eye), img.width(), img.height());
  EXPECT_GT(FractionOfImage(img, IsLiver), 0.05) << "liver covers too little of " << png;
  EXPECT_GT(FractionOfImage(img, IsGallbladder), 0.01) << "gallbladder covers too little of " << png;
  EXPECT_GT(FractionNear(img, gb_px, radius, IsGallbladder), 0.5)
      << "gallbladder not at its projection " << gb_px.transpose() << " in " << png;
  EXPECT_GT(FractionNear(img, liver_px, radius, IsLiver), 0.3)
      << "liver not at its projection " << liver_px.transpose() << " in " << png;
}

class LaparoscopeImageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scenario_ = LoadScenario(DefaultScenarioPath());
    meshes_ = LoadSceneMeshes(scenario_);
    dir_ = fs::temp_directory_path() / ("vesica_app_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  int Run(const std::string& args) {
    const std::string cmd = std::string(VESICA_TRAINER_EXE) + " " + args + " > " + (dir_ / "log.txt").string() + " 2>&1";
    return std::system(cmd.c_str());
  }

  Scenario scenario_;
  SceneMeshes meshes_;
  fs::path dir_;
};

TEST_F(LaparoscopeImageTest, HeadlessModeWritesAPictureWithBothOrgansWhereTheyProject) {
  const fs::path png = dir_ / "headless.png";
  ASSERT_EQ(Run("--headless --frames 3 --width 640 --height 360 --screenshot " + png.string()), 0);
  ExpectOrgansInPicture(png, scenario_, meshes_);
}

TEST_F(LaparoscopeImageTest, WindowShowsTheSameScene) {
  const fs::path png = dir_ / "window.png";
  ASSERT_EQ(Run("--width 640 --height 360 --quit-after-ms 2500 --grab " + png.string()), 0);
  ExpectOrgansInPicture(png, scenario_, meshes_);
}

TEST_F(LaparoscopeImageTest, BadScenarioFailsWithAMessageAndNoPicture) {
  const fs::path bad = dir_ / "bad.toml";
  std::ofstream(bad) << "[scenario]\nname = 3\n";
  const fs::path png = dir_ / "never.png";
  EXPECT_NE(Run("--headless --scenario " + bad.string() + " --screenshot " + png.string()), 0);
  EXPECT_FALSE(fs::exists(png));
  std::ifstream log(dir_ / "log.txt");
  const std::string text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(text.find("bad.toml:2: scenario.name: must be a string"), std::string::npos) << text;
}

TEST(ScreenProjectionTest, LookAtPointLandsInTheImageCentre) {
  LaparoscopeConfig scope;
  scope.position_m = {0.0, 0.2, -0.1};
  scope.look_at_m = {0.05, 0.0, 0.03};
  scope.view_angle_deg = 60;
  EXPECT_TRUE(testing::ProjectToPixel(scope, scope.look_at_m, 640, 360).isApprox(Eigen::Vector2d(320, 180), 1e-9));
  // A point above the target (cranial) appears above the centre.
  EXPECT_LT(testing::ProjectToPixel(scope, scope.look_at_m + Eigen::Vector3d(0, 0, 0.01), 640, 360).y(), 180);
}

}  // namespace
}  // namespace vesica::app
