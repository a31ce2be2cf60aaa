// Calot's triangle's anatomical variants as scenarios (issue 36): data/scenarios/calot-*.toml load,
// each has the property that makes it its variant (a short cystic duct, a low insertion beside
// the common bile duct, an artery crossing in front of the common hepatic duct as the laparoscope
// sees it), and each is the default scenario line for line but for the triangle, the hook's
// exchange, the name and description, the laparoscope's look_at_m and insertion_m (aimed at the
// triangle from closer in), and the context the simulated triangle replaces (the four
// structures' tubes and the static fat over the triangle).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "app/render/scene_meshes.h"
#include "app/render/scope_pose.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;
using physics::calot::TubeKind;
const fs::path kDir = fs::path(VESICA_SOURCE_DIR) / "data/scenarios";
const char* const kVariants[] = {"calot-standard.toml", "calot-short-duct.toml", "calot-low-insertion.toml",
                                 "calot-anterior-artery.toml"};

const CalotTubeConfig& TubeOf(const CalotTriangleConfig& triangle, TubeKind kind) {
  for (const CalotTubeConfig& t : triangle.tubes)
    if (t.kind == kind) return t;
  throw std::runtime_error(std::string("no tube of kind ") + TubeKindKey(kind));
}

double OuterRadius_m(const CalotTubeConfig& tube) {
  return tube.outer_radius_m.value_or(physics::calot::DefaultTubeMaterial(tube.kind).outer_radius_m);
}

double Length_m(const std::vector<Eigen::Vector3d>& polyline) {
  double length = 0;
  for (std::size_t k = 1; k < polyline.size(); ++k) length += (polyline[k] - polyline[k - 1]).norm();
  return length;
}

// Points every `step_m` along the polyline, both ends included.
std::vector<Eigen::Vector3d> Samples(const std::vector<Eigen::Vector3d>& polyline, double step_m) {
  std::vector<Eigen::Vector3d> out{polyline.front()};
  for (std::size_t k = 1; k < polyline.size(); ++k) {
    const Eigen::Vector3d a = polyline[k - 1], b = polyline[k];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_m)));
    for (int i = 1; i <= n; ++i) out.push_back(a + (b - a) * (static_cast<double>(i) / n));
  }
  return out;
}

double DistanceToPolyline_m(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& polyline) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < polyline.size(); ++k) {
    const Eigen::Vector3d a = polyline[k - 1], ab = polyline[k] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

// The default scenario's text and a variant's, each without what a variant may change: comments,
// the scenario's name and description, the hook's exchange line, the laparoscope's look_at_m and
// insertion_m, the [calot_triangle] tables, (from the default) the context the simulated
// triangle draws: the four structures' tubes and the fat over the triangle, and (from the
// variant) the backdrop the cleared triangle shows: the portal vein and the posterior peritoneum.
std::string WithoutWhatAVariantChanges(const fs::path& path) {
  static const std::vector<std::string> kReplacedContext = {"name = \"cystic duct\"",
                                                            "name = \"common hepatic duct\"",
                                                            "name = \"common bile duct\"",
                                                            "name = \"cystic artery\"",
                                                            "name = \"fat over the hepatocystic triangle\"",
                                                            "name = \"portal vein\"",
                                                            "name = \"posterior peritoneum\""};
  std::ifstream in(path);
  std::vector<std::vector<std::string>> blocks{{}};  // split at each [table] header
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) continue;
    line = line.substr(0, line.find("  #"));
    if (line.rfind("name = \"Laparoscopic", 0) == 0 || line.rfind("description =", 0) == 0 ||
        line.rfind("exchange =", 0) == 0)
      continue;
    if (!line.empty() && line[0] == '[') blocks.emplace_back();
    blocks.back().push_back(line);
  }
  std::stringstream out;
  for (const auto& block : blocks) {
    if (!block.empty() && block[0].find("calot_triangle") != std::string::npos) continue;
    const bool laparoscope = !block.empty() && block[0] == "[laparoscope]";
    if (block.size() > 1 && block[0] == "[[context_organs]]" &&
        std::find(kReplacedContext.begin(), kReplacedContext.end(),
                  block[1].substr(0, block[1].find_last_not_of(' ') + 1)) != kReplacedContext.end())
      continue;
    for (const std::string& l : block)
      if (!l.empty() && !(laparoscope && (l.rfind("look_at_m =", 0) == 0 || l.rfind("insertion_m =", 0) == 0)))
        out << l << "\n";
  }
  return out.str();
}

TEST(CalotVariantScenarios, EachLoadsWithItsTriangleAndTheHooksExchange) {
  for (const char* file : kVariants) {
    SCOPED_TRACE(file);
    const Scenario s = LoadScenario(kDir / file);
    ASSERT_TRUE(s.calot_triangle.has_value());
    EXPECT_EQ(s.name, "Laparoscopic cholecystectomy, Calot's triangle (" + s.calot_triangle->variant + ")");
    EXPECT_EQ(s.calot_triangle->tubes.size(), 4u);
    for (TubeKind kind :
         {TubeKind::kCysticDuct, TubeKind::kCysticArtery, TubeKind::kCommonHepaticDuct, TubeKind::kCommonBileDuct})
      EXPECT_NO_THROW(TubeOf(*s.calot_triangle, kind)) << TubeKindKey(kind);
    // Every cystic structure ends at the neck, the gallbladder's end of the default's cystic duct.
    EXPECT_LT((TubeOf(*s.calot_triangle, TubeKind::kCysticDuct).points_m.back() - s.calot_triangle->neck_m).norm(),
              1e-9);
    const InstrumentConfig& hook = s.instruments.at(1);
    EXPECT_EQ(hook.kind, InstrumentKind::kCauteryHook);
    EXPECT_EQ(hook.exchange, (std::vector<InstrumentKind>{InstrumentKind::kClipApplier, InstrumentKind::kScissors}));
    for (const ContextOrgan& organ : s.context_organs)
      EXPECT_TRUE(organ.name != "cystic duct" && organ.name != "cystic artery" && organ.name != "common bile duct" &&
                  organ.name != "common hepatic duct" && organ.name != "fat over the hepatocystic triangle")
          << organ.name << " is drawn as context as well as simulated";
    // Behind the triangle, tissue rather than a void; drawn only (the gallbladder rests on neither).
    int backdrop = 0;
    for (const ContextOrgan& organ : s.context_organs)
      if (organ.name == "portal vein" || organ.name == "posterior peritoneum") {
        ++backdrop;
        EXPECT_FALSE(organ.solid) << organ.name;
      }
    EXPECT_EQ(backdrop, 2);
  }
}

TEST(CalotVariantScenarios, EachIsTheDefaultButForTheTriangleTheExchangeAndTheNames) {
  const std::string default_text = WithoutWhatAVariantChanges(kDir / "cholecystectomy.toml");
  ASSERT_GT(default_text.size(), 1000u);
  for (const char* file : kVariants)
    EXPECT_EQ(default_text, WithoutWhatAVariantChanges(kDir / file))
        << file << " differs from cholecystectomy.toml beyond its triangle, exchange, names and replaced context tubes";
}

// The camera assistant's view of the triangle: the scope keeps its port, angle and view angle, and
// looks at the triangle (look_at within 15 mm of the standard triangle's centroid: neck, junction,
// hilum), from nearer than the default (its tip under 9 cm from look_at; the default's 11 cm).
TEST(CalotVariantScenarios, EachLaparoscopeLooksAtTheTriangleFromTheDefaultsPortAndCloser) {
  const Scenario defaults = LoadScenario(kDir / "cholecystectomy.toml");
  const CalotTriangleConfig& standard = *LoadScenario(kDir / "calot-standard.toml").calot_triangle;
  const Eigen::Vector3d centroid = (TubeOf(standard, TubeKind::kCysticDuct).points_m.front() + standard.neck_m +
                                    TubeOf(standard, TubeKind::kCommonHepaticDuct).points_m.front()) /
                                   3.0;
  const double default_distance_m = (defaults.laparoscope.look_at_m - ScopePoseOf(defaults.laparoscope).eye_W).norm();
  for (const char* file : kVariants) {
    SCOPED_TRACE(file);
    const LaparoscopeConfig scope = LoadScenario(kDir / file).laparoscope;
    EXPECT_EQ(scope.position_m, defaults.laparoscope.position_m);
    EXPECT_EQ(scope.scope_angle_deg, defaults.laparoscope.scope_angle_deg);
    EXPECT_EQ(scope.view_angle_deg, defaults.laparoscope.view_angle_deg);
    EXPECT_LT((scope.look_at_m - centroid).norm(), 0.015);
    const double distance_m = (scope.look_at_m - ScopePoseOf(scope).eye_W).norm();
    std::printf("scope tip to look_at: %.1f mm (default %.1f mm)\n", distance_m * 1e3, default_distance_m * 1e3);
    EXPECT_LT(distance_m, 0.09);
    EXPECT_GT(default_distance_m, 0.10);
  }
}

TEST(CalotVariantScenarios, TheStandardTriangleIsTheDefaultsContextTubes) {
  const Scenario standard = LoadScenario(kDir / "calot-standard.toml");
  const Scenario defaults = LoadScenario(kDir / "cholecystectomy.toml");
  auto context = [&](const std::string& name) {
    for (const ContextOrgan& o : defaults.context_organs)
      if (o.name == name) return o.points_m;
    throw std::runtime_error("the default has no context tube " + name);
  };
  // The default lists the cystic duct from the gallbladder down; the triangle from the patient's side.
  std::vector<Eigen::Vector3d> duct = context("cystic duct");
  std::reverse(duct.begin(), duct.end());
  EXPECT_EQ(TubeOf(*standard.calot_triangle, TubeKind::kCysticDuct).points_m, duct);
  EXPECT_EQ(TubeOf(*standard.calot_triangle, TubeKind::kCysticArtery).points_m, context("cystic artery"));
  EXPECT_EQ(TubeOf(*standard.calot_triangle, TubeKind::kCommonHepaticDuct).points_m, context("common hepatic duct"));
  EXPECT_EQ(TubeOf(*standard.calot_triangle, TubeKind::kCommonBileDuct).points_m, context("common bile duct"));
}

TEST(CalotVariantScenarios, TheShortDuctIsUnderTenMillimetres) {
  const Scenario s = LoadScenario(kDir / "calot-short-duct.toml");
  const double short_m = Length_m(TubeOf(*s.calot_triangle, TubeKind::kCysticDuct).points_m);
  const double standard_m =
      Length_m(TubeOf(*LoadScenario(kDir / "calot-standard.toml").calot_triangle, TubeKind::kCysticDuct).points_m);
  std::printf("cystic duct: %.1f mm short, %.1f mm standard\n", short_m * 1e3, standard_m * 1e3);
  EXPECT_LT(short_m, 0.010);
  EXPECT_GT(standard_m, 0.030);
  // The junction is where the common ducts meet: the common duct swings toward the gallbladder.
  const Eigen::Vector3d junction = TubeOf(*s.calot_triangle, TubeKind::kCysticDuct).points_m.front();
  EXPECT_LT((TubeOf(*s.calot_triangle, TubeKind::kCommonBileDuct).points_m.front() - junction).norm(), 1e-9);
  EXPECT_LT((TubeOf(*s.calot_triangle, TubeKind::kCommonHepaticDuct).points_m.back() - junction).norm(), 1e-9);
}

// Length of cystic duct whose wall lies within gap_m of the common bile duct's wall (and not
// inside it), sampled every 0.25 mm.
double LengthBesideTheBileDuct_m(const CalotTriangleConfig& triangle, double gap_m) {
  const CalotTubeConfig& duct = TubeOf(triangle, TubeKind::kCysticDuct);
  const CalotTubeConfig& bile = TubeOf(triangle, TubeKind::kCommonBileDuct);
  const double radii_m = OuterRadius_m(duct) + OuterRadius_m(bile);
  constexpr double kStep_m = 0.00025;
  double beside_m = 0;
  for (const Eigen::Vector3d& p : Samples(duct.points_m, kStep_m)) {
    const double wall_gap_m = DistanceToPolyline_m(p, bile.points_m) - radii_m;
    if (wall_gap_m >= -1e-9 && wall_gap_m <= gap_m) beside_m += kStep_m;
  }
  return beside_m;
}

TEST(CalotVariantScenarios, TheLowInsertionRunsBesideTheCommonBileDuct) {
  const Scenario low = LoadScenario(kDir / "calot-low-insertion.toml");
  const double beside_m = LengthBesideTheBileDuct_m(*low.calot_triangle, 0.004);
  const double standard_beside_m =
      LengthBesideTheBileDuct_m(*LoadScenario(kDir / "calot-standard.toml").calot_triangle, 0.004);
  std::printf("cystic duct within 4 mm of the common bile duct: %.1f mm (standard %.1f mm)\n", beside_m * 1e3,
              standard_beside_m * 1e3);
  EXPECT_GE(beside_m, 0.010);
  EXPECT_LT(standard_beside_m, 0.010);
  // It joins the common bile duct below the default's junction (the start of the common bile duct).
  const CalotTriangleConfig& t = *low.calot_triangle;
  const Eigen::Vector3d insertion = TubeOf(t, TubeKind::kCysticDuct).points_m.front();
  const Eigen::Vector3d upper_end = TubeOf(t, TubeKind::kCommonBileDuct).points_m.front();
  EXPECT_LT(DistanceToPolyline_m(insertion, TubeOf(t, TubeKind::kCommonBileDuct).points_m), 1e-4);  // the file's 0.1 mm
  EXPECT_GT((insertion - upper_end).norm(), 0.015);
}

// Seen from the laparoscope's tip, the artery's line of sight crosses the common hepatic duct and
// the artery is the nearer of the two there; false if the artery does not cross the duct.
bool ArteryCrossesInFrontOfTheHepaticDuct(const Scenario& s) {
  const Eigen::Vector3d eye = ScopePoseOf(s.laparoscope).eye_W;
  const CalotTubeConfig& artery = TubeOf(*s.calot_triangle, TubeKind::kCysticArtery);
  const CalotTubeConfig& duct = TubeOf(*s.calot_triangle, TubeKind::kCommonHepaticDuct);
  for (const Eigen::Vector3d& a : Samples(artery.points_m, 0.0002)) {
    const Eigen::Vector3d sight = (a - eye).normalized();
    for (const Eigen::Vector3d& c : Samples(duct.points_m, 0.0002)) {
      const double along_m = (c - eye).dot(sight);
      const double off_sight_m = ((c - eye) - along_m * sight).norm();
      // The line of sight through the artery's centre passes through the duct's middle half,
      // and the artery's far wall is in front of the duct's near wall.
      if (off_sight_m < 0.5 * OuterRadius_m(duct) &&
          (a - eye).norm() + OuterRadius_m(artery) < along_m - OuterRadius_m(duct))
        return true;
    }
  }
  return false;
}

TEST(CalotVariantScenarios, TheAnteriorArteryCrossesInFrontOfTheCommonHepaticDuct) {
  EXPECT_TRUE(ArteryCrossesInFrontOfTheHepaticDuct(LoadScenario(kDir / "calot-anterior-artery.toml")));
  EXPECT_FALSE(ArteryCrossesInFrontOfTheHepaticDuct(LoadScenario(kDir / "calot-standard.toml")));
}

// Each variant runs in a session: the triangle's neck finds its gallbladder nodes, the tubes stay
// finite while the instruments wait, the fat hides every structure at the start (the critical
// view is not there to be had), and the session's metrics say it has the Calot step.
TEST(CalotVariantScenarios, EachRunsInADissectionSessionWithItsFatCovering) {
  for (const char* file : kVariants) {
    SCOPED_TRACE(file);
    const Scenario s = LoadScenario(kDir / file);
    DissectionSession session(BuildDissectionModelFor(s, LoadSceneMeshes(s)), DefaultCauteryParams(),
                              CalotSessionSetupFor(s));
    ASSERT_NE(session.calot_metrics(), nullptr);
    device::InputFrame frame;
    for (int i = 0; i < 2; ++i) frame.instruments[i].pose.insertion_m = s.instruments[i].initial_insertion_m;
    for (int k = 0; k < 40; ++k) session.Step(frame);
    EXPECT_FALSE(session.case_ended());
    for (const physics::calot::TubePiece& piece : session.calot_tubes()->pieces())
      EXPECT_TRUE(piece.rod.positions_m().allFinite());
    for (const calot::StructureState& st : session.calot_step()->last_snapshot().structures)
      EXPECT_EQ(st.visible_fraction, 0.0) << st.name;
    const SessionMetrics m = session.metrics();
    EXPECT_TRUE(m.calot_step);
    EXPECT_FALSE(m.cvs_achieved);
    EXPECT_EQ(m.bile_duct_injuries, 0);
  }
}

}  // namespace
}  // namespace vesica::app
