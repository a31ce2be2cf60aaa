// The surgeon's-view scenario's own keys (issue 30): [patient] gives gravity on the gallbladder
// from the table's tilt, [assistant_retraction] holds the fundus. Both are optional (the default
// scenario has neither: no gravity, no hold); bad values are refused naming file, line and key.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;

const fs::path kDir = fs::path(VESICA_SOURCE_DIR) / "data/scenarios";

std::string SurgeonViewText() {
  std::ifstream in(kDir / "cholecystectomy.toml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Scenario Parse(const std::string& text) { return ParseScenario(text, "surgeon-view.toml", kDir); }

// The text with `from` replaced by `to` (which must be there).
std::string With(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("not in the scenario: " + from);
  return text.replace(at, from.size(), to);
}

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PatientAndRetractionKeys, TheSurgeonViewTiltsThePatientAndHoldsTheFundus) {
  const Scenario s = Parse(SurgeonViewText());
  ASSERT_TRUE(s.patient.given);
  EXPECT_DOUBLE_EQ(s.patient.reverse_trendelenburg_deg, 15.0);
  EXPECT_DOUBLE_EQ(s.patient.left_tilt_deg, 15.0);
  const Eigen::Vector3d g = GravityInPatientFrame(s.patient);
  // Head up: gravity toward the feet; left side down: toward the patient's left (+x).
  const double a = 15.0 * std::numbers::pi / 180.0;
  EXPECT_NEAR(g.norm(), s.patient.gravity_m_per_s2, 1e-12);
  EXPECT_NEAR(g.z(), -s.patient.gravity_m_per_s2 * std::sin(a), 1e-12);
  EXPECT_NEAR(g.x(), s.patient.gravity_m_per_s2 * std::sin(a) * std::cos(a), 1e-12);
  EXPECT_LT(g.y(), 0.0) << "still mostly posterior";
  ASSERT_TRUE(s.assistant_retraction.has_value());
  EXPECT_GT(s.assistant_retraction->displacement_m.z(), 0.0) << "targets displaced cranially";

  // Into the physics: gravity and the held fundus nodes.
  const SceneMeshes meshes = LoadSceneMeshes(s);
  const physics::DissectionModelInputs in = MakeDissectionInputs(s, meshes);
  EXPECT_TRUE(in.settings.gravity_m_per_s2.isApprox(g));
  EXPECT_TRUE(in.settings.assistant_retraction.enabled);
  EXPECT_TRUE(in.settings.assistant_retraction.grasp_point_m.isApprox(s.assistant_retraction->grasp_point_m));
}

// The default is the surgeon's view: the patient tilted and the fundus held. The overview layout,
// whose scope looks down on the bed, has neither: no gravity, no assistant.
TEST(PatientAndRetractionKeys, TheDefaultTiltsAndHoldsTheOverviewHasNeither) {
  const Scenario by_default = LoadScenario(DefaultScenarioPath());
  EXPECT_TRUE(by_default.patient.given);
  EXPECT_TRUE(by_default.assistant_retraction.has_value());
  const Scenario s =
      LoadScenario(kDir / "cholecystectomy-overview.toml");
  EXPECT_FALSE(s.patient.given);
  EXPECT_TRUE(GravityInPatientFrame(s.patient).isZero());
  EXPECT_FALSE(s.assistant_retraction.has_value());
  const physics::DissectionModelInputs in = MakeDissectionInputs(s, LoadSceneMeshes(s));
  EXPECT_TRUE(in.settings.gravity_m_per_s2.isZero());
  EXPECT_FALSE(in.settings.assistant_retraction.enabled);
}

TEST(PatientAndRetractionKeys, BadValuesAreRefusedByName) {
  const std::string text = SurgeonViewText();
  EXPECT_NE(ErrorOf(With(text, "left_tilt_deg = 15.0", "left_tilt_deg = 60.0")).find("patient.left_tilt_deg"),
            std::string::npos);
  EXPECT_NE(ErrorOf(With(text, "left_tilt_deg = 15.0", "left_tilt = 15.0")).find("patient.left_tilt: unknown key"),
            std::string::npos);
  EXPECT_NE(ErrorOf(With(text, "gravity_m_per_s2 = 2.0", "gravity_m_per_s2 = -1.0")).find("patient.gravity_m_per_s2"),
            std::string::npos);
  EXPECT_NE(ErrorOf(With(text, "radius_m = 0.012", "radius_m = 0.5")).find("assistant_retraction.radius_m"),
            std::string::npos);
  EXPECT_NE(ErrorOf(With(text, "displacement_m = [0.0, 0.0, 0.003]", "displacement_m = [0.0, 0.0, 0.3]"))
                .find("assistant_retraction.displacement_m: must be at most 0.05 m long"),
            std::string::npos);
  EXPECT_NE(ErrorOf(With(text, "stiffness_N_per_m = 40.0", "stiffness_N_per_m = 0.0"))
                .find("assistant_retraction.stiffness_N_per_m"),
            std::string::npos);
  const std::string missing = ErrorOf(With(text, "grasp_point_m = [", "grasp_point = ["));
  EXPECT_NE(missing.find("assistant_retraction.grasp_point_m"), std::string::npos) << missing;
  // A grasp point away from the gallbladder holds nothing: the physics says so.
  const Scenario far =
      Parse(With(text, "grasp_point_m = [-0.0651, 0.0633, 0.0482]", "grasp_point_m = [0.1, 0.0, 0.0]"));
  const physics::DissectionModelInputs in = MakeDissectionInputs(far, LoadSceneMeshes(far));
  try {
    physics::MakeAssistantRetraction(in.gallbladder_mesh, in.settings.assistant_retraction);
    ADD_FAILURE() << "a retraction that holds nothing was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("holds no gallbladder node"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesica::app
