// Renders the default scenario the way a user would (the vesica-trainer binary, headless and as a
// window) and checks the picture: the organs must be where an independent camera model says
// they project, in their own colours. Runs under its own Xvfb (see CMakeLists.txt).

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>
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

// Pixels covered by the mesh's projection (its silhouette, every triangle rasterised).
std::vector<bool> Footprint(const physics::TriangleMesh& mesh, const LaparoscopeConfig& scope, int w, int h) {
  std::vector<bool> mask(static_cast<std::size_t>(w) * h, false);
  std::vector<Eigen::Vector2d> px(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    px[v] = testing::ProjectToPixel(scope, mesh.vertices.row(v).transpose(), w, h);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Eigen::Vector2d a = px[mesh.triangles(f, 0)], b = px[mesh.triangles(f, 1)], c = px[mesh.triangles(f, 2)];
    const auto cross = [](Eigen::Vector2d u, Eigen::Vector2d v) { return u.x() * v.y() - u.y() * v.x(); };
    const double area = cross(b - a, c - a);
    if (std::abs(area) < 1e-12) continue;
    const int c0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int c1 = std::min(w - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int r0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int r1 = std::min(h - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int row = r0; row <= r1; ++row)
      for (int col = c0; col <= c1; ++col) {
        const Eigen::Vector2d p(col + 0.5, row + 0.5);
        const double u = cross(b - a, p - a) / area, v = cross(c - b, p - b) / area, t = cross(a - c, p - c) / area;
        if (u >= 0 && v >= 0 && t >= 0) mask[static_cast<std::size_t>(row) * w + col] = true;
      }
  }
  return mask;
}

// Fraction of the pixels selected by `select` that `is` classifies as the organ.
template <typename Select>
double Fraction(const Image& img, Select select, bool (*is)(Rgb)) {
  int hits = 0, total = 0;
  for (int row = 0; row < img.height(); ++row)
    for (int col = 0; col < img.width(); ++col)
      if (select(static_cast<std::size_t>(row) * img.width() + col)) {
        ++total;
        hits += is(img.at(col, row));
      }
  return total ? static_cast<double>(hits) / total : 0.0;
}

bool IsOrgan(Rgb c) { return IsLiver(c) || IsGallbladder(c); }

// The picture must show each organ inside its projected silhouette (an independent camera model),
// in its colour, and nothing organ-coloured outside them.
void ExpectOrgansInPicture(const fs::path& png, const Scenario& s, const SceneMeshes& m) {
  ASSERT_TRUE(fs::exists(png)) << png;
  const Image img(png);
  ASSERT_GT(img.width(), 0);
  const int w = img.width(), h = img.height();
  const auto liver = Footprint(m.liver, s.laparoscope, w, h);
  const auto gb = Footprint(m.gallbladder_surface, s.laparoscope, w, h);
  const auto count = [](const std::vector<bool>& v) { return std::count(v.begin(), v.end(), true); };
  ASSERT_GT(count(liver), w * h / 20) << "the default view should frame the liver";
  ASSERT_GT(count(gb), w * h / 100) << "the default view should frame the gallbladder";
  // 0.75: the scope's light falls off with distance (the far liver is too dark to classify) and
  // in the window the diagnostics panel covers part of the liver.
  EXPECT_GT(Fraction(img, [&](std::size_t i) { return liver[i] && !gb[i]; }, IsLiver), 0.75)
      << "liver missing from its silhouette in " << png;
  EXPECT_GT(Fraction(img, [&](std::size_t i) { return gb[i]; }, IsGallbladder), 0.6)
      << "gallbladder missing from its silhouette in " << png;
  EXPECT_LT(Fraction(img, [&](std::size_t i) { return !liver[i] && !gb[i]; }, IsOrgan), 0.02)
      << "organ colours outside the organs' silhouettes in " << png;
}

// The overview layout (the scope looking down on the liver bed): the image checks were made for
// its open view of both organs.
fs::path OverviewScenarioPath() { return fs::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy-overview.toml"; }

class LaparoscopeImageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scenario_ = LoadScenario(OverviewScenarioPath());
    meshes_ = LoadSceneMeshes(scenario_);
    dir_ = fs::temp_directory_path() / ("vesica_app_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The overview scenario with only the simulated organs in view: its static context (other
  // organs, the peritoneum) would be organ-coloured pixels outside the liver's and the
  // gallbladder's silhouettes. Written to the test's folder with absolute mesh paths.
  fs::path OrgansOnlyScenario() {
    std::ifstream in(OverviewScenarioPath());
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text = text.substr(0, text.find("[[context_organs]]"));
    const std::string anatomy = "\"" + (OverviewScenarioPath().parent_path() / "../anatomy/").lexically_normal().string();
    for (std::size_t at; (at = text.find("\"../anatomy/")) != std::string::npos;) text.replace(at, 12, anatomy);
    const std::string wall = "opacity = 1.0";
    if (const auto at = text.find(wall); at != std::string::npos) text.replace(at, wall.size(), "opacity = 0.0");
    const fs::path path = dir_ / "organs_only.toml";
    std::ofstream(path) << text;
    return path;
  }

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
  ASSERT_EQ(Run("--headless --frames 3 --width 640 --height 360 --scenario " + OrgansOnlyScenario().string() +
                " --screenshot " + png.string()),
            0);
  ExpectOrgansInPicture(png, scenario_, meshes_);
}

TEST_F(LaparoscopeImageTest, WindowShowsTheSameScene) {
  const fs::path png = dir_ / "window.png";
  ASSERT_EQ(Run("--width 640 --height 360 --records none --quit-after-ms 2500 --scenario " +
                OrgansOnlyScenario().string() + " --grab " + png.string()),
            0);
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

TEST(ScreenProjectionTest, SeenFromTheFeetThePatientsRightIsOnTheLeftAndTheWallAtTheTop) {
  // A scope from the umbilicus looking cranially, as at the operation: the liver's right lobe
  // (-x, the patient's right) on the image's left, the anterior wall (+y) at its top.
  LaparoscopeConfig scope;
  scope.position_m = {0.0, 0.1, -0.1};
  scope.look_at_m = {0.0, 0.0, 0.05};
  scope.insertion_m = 0.05;
  scope.view_angle_deg = 50;
  const Eigen::Vector2d centre = testing::ProjectToPixel(scope, scope.look_at_m, 640, 360);
  EXPECT_LT(testing::ProjectToPixel(scope, scope.look_at_m + Eigen::Vector3d(-0.01, 0, 0), 640, 360).x(), centre.x());
  EXPECT_GT(testing::ProjectToPixel(scope, scope.look_at_m + Eigen::Vector3d(0.01, 0, 0), 640, 360).x(), centre.x());
  EXPECT_LT(testing::ProjectToPixel(scope, scope.look_at_m + Eigen::Vector3d(0, 0.01, 0), 640, 360).y(), centre.y());
}

}  // namespace
}  // namespace vesica::app
