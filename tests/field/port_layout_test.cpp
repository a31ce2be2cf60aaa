// The ports where a surgeon puts them (issue 30): the American four-port layout of the default
// (left hand's grasper right subcostal, right hand's hook epigastric) and the French position
// (cholecystectomy-french.toml: the surgeon between the legs, the grasper in the right flank, the
// hook in the left hypochondrium). In both the hands are not crossed on screen: the left hand's
// shaft enters the picture left of the right hand's, on its way to the field (the independent
// pinhole model of tests/app/screen_projection.h). The French file is the default but for its
// name, description, header and trocars.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../app/screen_projection.h"
#include "app/scenario/scenario_loader.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;
const fs::path kDir = fs::path(VESICA_SOURCE_DIR) / "data/scenarios";
constexpr int kWidth = 1280, kHeight = 720;

const Trocar& TrocarNamed(const Scenario& s, const std::string& name) {
  for (const Trocar& t : s.trocars)
    if (t.name == name) return t;
  throw std::runtime_error("no trocar " + name);
}

// Mean picture column of the part of the line from `port` to `target` the scope sees, or NaN.
double MeanColumnInView(const LaparoscopeConfig& scope, const Eigen::Vector3d& port, const Eigen::Vector3d& target) {
  const Eigen::Vector3d forward = (scope.look_at_m - scope.position_m).normalized();
  const Eigen::Vector3d eye = scope.position_m + scope.insertion_m * forward;
  double sum = 0;
  int n = 0;
  for (int k = 0; k <= 100; ++k) {
    const Eigen::Vector3d p = port + (k / 100.0) * (target - port);
    if ((p - eye).dot(forward) <= 0.005) continue;
    const Eigen::Vector2d px = testing::ProjectToPixel(scope, p, kWidth, kHeight);
    if (px.x() < 0 || px.x() >= kWidth || px.y() < 0 || px.y() >= kHeight) continue;
    sum += px.x();
    ++n;
  }
  return n > 0 ? sum / n : std::numeric_limits<double>::quiet_NaN();
}

std::string WithoutPortsAndNames(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream out;
  std::string line;
  bool in_trocar = false;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0 || line.rfind("name = \"Laparoscopic", 0) == 0 || line.rfind("description =", 0) == 0)
      continue;
    if (line == "[[trocars]]")
      in_trocar = true;
    else if (!line.empty() && line[0] == '[')
      in_trocar = false;
    if (in_trocar && line.rfind("position_m", 0) == 0) continue;
    out << line.substr(0, line.find("  #")) << "\n";
  }
  return out.str();
}

TEST(PortLayout, TheHandsAreNotCrossedOnScreenInEitherPosition) {
  for (const char* file : {"cholecystectomy.toml", "cholecystectomy-french.toml"}) {
    const Scenario s = LoadScenario(kDir / file);
    const Eigen::Vector3d field = s.laparoscope.look_at_m;
    const double left = MeanColumnInView(s.laparoscope, TrocarNamed(s, "left").position_m, field);
    const double right = MeanColumnInView(s.laparoscope, TrocarNamed(s, "right").position_m, field);
    std::printf("%s: the left hand's shaft at column %.0f, the right hand's at %.0f of %d\n", file, left, right,
                kWidth);
    ASSERT_FALSE(std::isnan(left)) << file;
    ASSERT_FALSE(std::isnan(right)) << file;
    EXPECT_LT(left, right) << file << ": the hands cross on screen";
    EXPECT_GT(right - left, 0.1 * kWidth) << file << ": the two instruments come from apart";
  }
}

TEST(PortLayout, TheFrenchPositionMovesOnlyThePorts) {
  const Scenario american = LoadScenario(kDir / "cholecystectomy.toml");
  const Scenario french = LoadScenario(kDir / "cholecystectomy-french.toml");
  EXPECT_EQ(WithoutPortsAndNames(kDir / "cholecystectomy.toml"),
            WithoutPortsAndNames(kDir / "cholecystectomy-french.toml"))
      << "cholecystectomy-french.toml differs from cholecystectomy.toml beyond its ports";
  // The surgeon between the legs: the grasper from the patient's right flank (further right and
  // lower than the subcostal port), the hook from the left hypochondrium (left of the midline).
  EXPECT_LT(TrocarNamed(french, "left").position_m.x(), TrocarNamed(american, "left").position_m.x());
  EXPECT_LT(TrocarNamed(french, "left").position_m.z(), TrocarNamed(american, "left").position_m.z());
  EXPECT_GT(TrocarNamed(french, "right").position_m.x(), 0.04);
  EXPECT_LT(TrocarNamed(american, "right").position_m.x(), 0.02);
}

}  // namespace
}  // namespace vesica::app
