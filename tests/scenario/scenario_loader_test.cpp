#include "app/scenario/scenario_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>

namespace vesica::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A complete, valid scenario; the malformed cases below each change one thing in it.
constexpr const char* kValid = R"([scenario]
name = "test"

[liver]
model = "bem"
surface_mesh = "liver.vtk"
youngs_modulus_Pa = 170000.0
poisson_ratio = 0.4

[gallbladder]
model = "fem"
volume_mesh = "gb.vtu"
youngs_modulus_Pa = 2300.0
poisson_ratio = 0.45
element = "linear"
solver = "cholmod"

[connective_tissue]
stiffness_N_per_m = 20.0

[abdominal_wall]
surface_mesh = "wall.vtk"

[[trocars]]
name = "left"
position_m = [-0.1, 0.1, 0.0]

[[trocars]]
name = "right"
position_m = [0.1, 0.1, 0.0]

[laparoscope]
position_m = [0.0, 0.15, -0.1]
look_at_m = [0.0, 0.0, 0.0]

[[instruments]]
name = "grasper"
kind = "grasper"
trocar = "left"

[[instruments]]
name = "hook"
kind = "cautery_hook"
trocar = "right"
input = "emulated_arm"
can_node_id = 2
)";

class ScenarioLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vesica_scenario_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    for (const char* name : {"liver.vtk", "gb.vtu", "wall.vtk"}) std::ofstream(dir_ / name) << "placeholder";
  }
  void TearDown() override { fs::remove_all(dir_); }

  Scenario Parse(const std::string& text) { return ParseScenario(text, "case.toml", dir_); }

  // Replaces `from` (which must occur once) and returns the error message of parsing the result.
  std::string ErrorAfter(const std::string& from, const std::string& to) {
    std::string text = kValid;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from << " occurs twice";
    text.replace(at, from.size(), to);
    try {
      Parse(text);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "no error";
  }

  // 1-based line of the first occurrence of `needle` in the valid text after the same replacement.
  static int LineOf(const std::string& needle) {
    const std::string text = kValid;
    const auto at = text.find(needle);
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  }

  fs::path dir_;
};

TEST_F(ScenarioLoaderTest, ValidFileGivesAllValuesInSiUnits) {
  const Scenario s = Parse(kValid);
  EXPECT_EQ(s.name, "test");
  EXPECT_EQ(s.liver.surface_mesh, (dir_ / "liver.vtk").lexically_normal());
  EXPECT_DOUBLE_EQ(s.liver.material.youngs_modulus_Pa, 170000.0);
  EXPECT_DOUBLE_EQ(s.gallbladder.material.poisson_ratio, 0.45);
  EXPECT_EQ(s.gallbladder.element, FemElement::kLinear);
  EXPECT_EQ(s.gallbladder.solver, FemSolver::kCholmod);
  EXPECT_DOUBLE_EQ(s.connective_tissue.attach_offset_m, 0.005);  // default
  ASSERT_EQ(s.trocars.size(), 2u);
  EXPECT_TRUE(s.trocar("right").position_m.isApprox(Eigen::Vector3d(0.1, 0.1, 0.0)));
  ASSERT_EQ(s.instruments.size(), 2u);
  EXPECT_EQ(s.instruments[0].input, InputKind::kKeyboard);  // default
  EXPECT_EQ(s.instruments[1].kind, InstrumentKind::kCauteryHook);
  EXPECT_EQ(s.instruments[1].input, InputKind::kEmulatedArm);
  EXPECT_EQ(s.instruments[1].can_node_id, 2);
  EXPECT_THROW(s.trocar("middle"), ScenarioError);
}

TEST_F(ScenarioLoaderTest, SyntaxErrorNamesTheLine) {
  EXPECT_THAT(ErrorAfter("stiffness_N_per_m = 20.0", "stiffness_N_per_m = = 20.0"),
              HasSubstr("case.toml:" + std::to_string(LineOf("stiffness_N_per_m")) + ": syntax error"));
}

TEST_F(ScenarioLoaderTest, PoissonRatioAtIncompressibleLimitIsRejected) {
  EXPECT_EQ(ErrorAfter("poisson_ratio = 0.45", "poisson_ratio = 0.5"),
            "case.toml:" + std::to_string(LineOf("poisson_ratio = 0.45")) +
                ": gallbladder.poisson_ratio: must be in (-1, 0.5), got 0.5");
}

TEST_F(ScenarioLoaderTest, NonPositiveYoungsModulusIsRejected) {
  EXPECT_THAT(ErrorAfter("youngs_modulus_Pa = 170000.0", "youngs_modulus_Pa = -5.0"),
              HasSubstr("case.toml:" + std::to_string(LineOf("youngs_modulus_Pa = 170000.0")) +
                        ": liver.youngs_modulus_Pa: must be > 0, got -5"));
}

TEST_F(ScenarioLoaderTest, WrongTypeIsNamed) {
  EXPECT_THAT(ErrorAfter("stiffness_N_per_m = 20.0", "stiffness_N_per_m = \"stiff\""),
              HasSubstr("case.toml:" + std::to_string(LineOf("stiffness_N_per_m")) +
                        ": connective_tissue.stiffness_N_per_m: must be a number, got a string"));
}

TEST_F(ScenarioLoaderTest, MissingKeyNamesItsTable) {
  // The line is the table header's, where the key should have been.
  EXPECT_THAT(
      ErrorAfter("youngs_modulus_Pa = 2300.0\n", ""),
      HasSubstr("case.toml:" + std::to_string(LineOf("[gallbladder]")) + ": gallbladder.youngs_modulus_Pa: missing"));
}

TEST_F(ScenarioLoaderTest, UnknownKeyIsATypo) {
  EXPECT_THAT(ErrorAfter("poisson_ratio = 0.4\n", "poisson_ratio = 0.4\npoison_ratio = 0.3\n"),
              HasSubstr("case.toml:" + std::to_string(LineOf("poisson_ratio = 0.4") + 1) +
                        ": liver.poison_ratio: unknown key"));
}

TEST_F(ScenarioLoaderTest, MissingMeshFileIsNamed) {
  EXPECT_THAT(ErrorAfter("\"gb.vtu\"", "\"nowhere.vtu\""), HasSubstr("case.toml:" + std::to_string(LineOf("gb.vtu")) +
                                                                     ": gallbladder.volume_mesh: file not found: "));
}

TEST_F(ScenarioLoaderTest, PositionWithTwoComponentsIsRejected) {
  EXPECT_THAT(ErrorAfter("[0.1, 0.1, 0.0]", "[0.1, 0.1]"),
              HasSubstr("case.toml:" + std::to_string(LineOf("[0.1, 0.1, 0.0]")) +
                        ": trocars[1].position_m: must be an array of 3 numbers [x, y, z], got an array of 2"));
}

TEST_F(ScenarioLoaderTest, InstrumentOnUnknownTrocarIsRejected) {
  EXPECT_THAT(ErrorAfter("trocar = \"right\"", "trocar = \"middle\""),
              HasSubstr("case.toml:" + std::to_string(LineOf("trocar = \"right\"")) +
                        ": instruments[1].trocar: no trocar named 'middle'"));
}

TEST_F(ScenarioLoaderTest, UnknownChoiceListsTheValidOnes) {
  EXPECT_THAT(ErrorAfter("input = \"emulated_arm\"", "input = \"joystick\""),
              HasSubstr("case.toml:" + std::to_string(LineOf("input = ")) +
                        ": instruments[1].input: unknown value 'joystick' (expected one of: keyboard, replay, "
                        "emulated_arm, can_arm)"));
}

TEST_F(ScenarioLoaderTest, EverySolverChoiceParses) {
  std::string text = kValid;
  const std::string from = "solver = \"cholmod\"";
  text.replace(text.find(from), from.size(), "solver = \"rotated_factor_pcg\"");
  EXPECT_EQ(Parse(text).gallbladder.solver, FemSolver::kRotatedFactorPcg);
  EXPECT_THAT(ErrorAfter(from, "solver = \"gauss\""),
              HasSubstr("unknown value 'gauss' (expected one of: pcg, cholmod, rotated_factor_pcg)"));
}

TEST_F(ScenarioLoaderTest, CanNodeIdOutOfRange) {
  EXPECT_THAT(ErrorAfter("can_node_id = 2", "can_node_id = 200"),
              HasSubstr("case.toml:" + std::to_string(LineOf("can_node_id")) +
                        ": instruments[1].can_node_id: must be in [1, 127], got 200"));
}

TEST_F(ScenarioLoaderTest, DuplicateInstrumentName) {
  EXPECT_THAT(ErrorAfter("name = \"hook\"", "name = \"grasper\""),
              HasSubstr("case.toml:" + std::to_string(LineOf("name = \"hook\"")) +
                        ": instruments[1].name: duplicate instrument 'grasper'"));
}

TEST_F(ScenarioLoaderTest, MissingTableIsNamed) {
  EXPECT_THAT(ErrorAfter("[connective_tissue]\nstiffness_N_per_m = 20.0\n", ""),
              HasSubstr(": connective_tissue: missing table [connective_tissue]"));
}

TEST_F(ScenarioLoaderTest, IntegerBeyondIntIsRefusedNotWrapped) {
  // 4294967297 = 2^32 + 1 once narrowed to int as 1, a valid node id.
  EXPECT_THAT(ErrorAfter("can_node_id = 2", "can_node_id = 4294967297"),
              HasSubstr("case.toml:" + std::to_string(LineOf("can_node_id")) +
                        ": instruments[1].can_node_id: must be in [1, 127], got 4294967297"));
  EXPECT_THAT(ErrorAfter("can_node_id = 2", "can_node_id = -4294967295"),
              HasSubstr("instruments[1].can_node_id: must be in [1, 127], got -4294967295"));
}

TEST_F(ScenarioLoaderTest, NanAndInfinityAreRefusedForEveryNumber) {
  EXPECT_THAT(ErrorAfter("stiffness_N_per_m = 20.0", "stiffness_N_per_m = inf"),
              HasSubstr("case.toml:" + std::to_string(LineOf("stiffness_N_per_m")) +
                        ": connective_tissue.stiffness_N_per_m: must be a finite number, got inf"));
  EXPECT_THAT(ErrorAfter("poisson_ratio = 0.45", "poisson_ratio = nan"),
              HasSubstr("gallbladder.poisson_ratio: must be a finite number, got nan"));
  EXPECT_THAT(ErrorAfter("[0.1, 0.1, 0.0]", "[0.1, -inf, 0.0]"),
              HasSubstr("case.toml:" + std::to_string(LineOf("[0.1, 0.1, 0.0]")) +
                        ": trocars[1].position_m: element 1 must be a finite number, got -inf"));
  EXPECT_THAT(ErrorAfter("look_at_m = [0.0, 0.0, 0.0]", "look_at_m = [0.0, nan, 0.0]"),
              HasSubstr("laparoscope.look_at_m: element 1 must be a finite number, got nan"));
  EXPECT_THAT(ErrorAfter("stiffness_N_per_m = 20.0\n", "stiffness_N_per_m = 20.0\ndamping_Ns_per_m = +inf\n"),
              HasSubstr("connective_tissue.damping_Ns_per_m: must be a finite number, got inf"));
  EXPECT_THAT(ErrorAfter("surface_mesh = \"wall.vtk\"\n", "surface_mesh = \"wall.vtk\"\nopacity = nan\n"),
              HasSubstr("abdominal_wall.opacity: must be a finite number, got nan"));
}

TEST_F(ScenarioLoaderTest, RefusedValuesPrintEveryDigitTheyHave) {
  EXPECT_THAT(ErrorAfter("poisson_ratio = 0.45", "poisson_ratio = 0.50000000001"),
              HasSubstr("gallbladder.poisson_ratio: must be in (-1, 0.5), got 0.50000000001"));
  EXPECT_THAT(ErrorAfter("youngs_modulus_Pa = 170000.0", "youngs_modulus_Pa = -1e-300"),
              HasSubstr("liver.youngs_modulus_Pa: must be > 0, got -1e-300"));
  EXPECT_THAT(ErrorAfter("surface_mesh = \"wall.vtk\"\n", "surface_mesh = \"wall.vtk\"\nopacity = 1.0000001\n"),
              HasSubstr("abdominal_wall.opacity: must be in [0, 1], got 1.0000001"));
}

TEST_F(ScenarioLoaderTest, DirectoryGivenAsMeshIsNamedAsSuch) {
  fs::create_directories(dir_ / "meshes");
  EXPECT_THAT(ErrorAfter("\"gb.vtu\"", "\"meshes\""),
              HasSubstr("case.toml:" + std::to_string(LineOf("gb.vtu")) +
                        ": gallbladder.volume_mesh: is a directory, not a file: " + (dir_ / "meshes").string()));
}

TEST_F(ScenarioLoaderTest, DirectoryGivenAsScenarioIsNamedAsSuch) {
  try {
    LoadScenario(dir_);
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()), dir_.string() + ": is a directory, not a scenario file");
  }
}

TEST_F(ScenarioLoaderTest, UnreadableFileIsNamed) {
  try {
    LoadScenario(dir_ / "absent.toml");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_THAT(e.what(), HasSubstr("absent.toml: cannot open scenario file"));
  }
}

}  // namespace
}  // namespace vesica::app

namespace vesica::app {
namespace {

// The laparoscope's tip and the field's static context organs (issue 30).
class ScenarioFieldTest : public ScenarioLoaderTest {};

TEST_F(ScenarioFieldTest, ScopeInsertionAndContextOrgansAreRead) {
  std::string text = kValid;
  text += R"(
[[context_organs]]
name = "duodenum"
shape = "tube"
points_m = [[0.0, 0.0, 0.0], [0.01, 0.0, 0.0], [0.02, 0.01, 0.0]]
radius_m = 0.014
rgb = [0.8, 0.5, 0.4]

[[context_organs]]
name = "fat"
shape = "ellipsoid"
centre_m = [0.0, 0.01, 0.02]
semi_axes_m = [0.01, 0.02, 0.03]
rgb = [0.9, 0.7, 0.4]
)";
  const Scenario s = Parse(text);
  EXPECT_DOUBLE_EQ(s.laparoscope.insertion_m, 0.07);  // the default
  ASSERT_EQ(s.context_organs.size(), 2u);
  EXPECT_EQ(s.context_organs[0].name, "duodenum");
  EXPECT_EQ(s.context_organs[0].shape, ContextOrgan::Shape::kTube);
  ASSERT_EQ(s.context_organs[0].points_m.size(), 3u);
  EXPECT_TRUE(s.context_organs[0].points_m[2].isApprox(Eigen::Vector3d(0.02, 0.01, 0.0)));
  EXPECT_DOUBLE_EQ(s.context_organs[0].radius_m, 0.014);
  EXPECT_EQ(s.context_organs[1].shape, ContextOrgan::Shape::kEllipsoid);
  EXPECT_TRUE(s.context_organs[1].semi_axes_m.isApprox(Eigen::Vector3d(0.01, 0.02, 0.03)));
  EXPECT_TRUE(Parse(kValid).context_organs.empty());  // optional
}

TEST_F(ScenarioFieldTest, BadScopeInsertionAndContextOrgansAreNamed) {
  // The scope's tip past what it looks at (the line is 18 cm long).
  EXPECT_NE(ErrorAfter("look_at_m = [0.0, 0.0, 0.0]\n", "look_at_m = [0.0, 0.0, 0.0]\ninsertion_m = 0.2\n")
                .find("laparoscope.insertion_m: puts the scope's tip within 1 cm of (or past) look_at_m"),
            std::string::npos);
  const auto error_of = [&](const std::string& organ) {
    try {
      Parse(std::string(kValid) + "\n[[context_organs]]\n" + organ);
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("name = \"d\"\nshape = \"tube\"\npoints_m = [[0.0, 0.0, 0.0]]\nradius_m = 0.01\nrgb = [1, 1, 1]\n")
                .find("points_m: must be an array of at least 2 [x, y, z] points"),
            std::string::npos);
  EXPECT_NE(error_of("name = \"d\"\nshape = \"blob\"\nrgb = [1, 1, 1]\n").find("unknown value 'blob'"),
            std::string::npos);
  EXPECT_NE(error_of("name = \"f\"\nshape = \"ellipsoid\"\ncentre_m = [0, 0, 0]\nsemi_axes_m = [0.01, -0.02, 0.03]\n"
                     "rgb = [1, 1, 1]\n")
                .find("semi_axes_m: each must be in (0, 0.3) m"),
            std::string::npos);
  EXPECT_NE(error_of("name = \"d\"\nshape = \"tube\"\npoints_m = [[0.0, 0.0, 0.0], [0.0, 0.0, nan]]\nradius_m = 0.01\n"
                     "rgb = [1, 1, 1]\n")
                .find("point 1 element 2 must be a finite number"),
            std::string::npos);
  EXPECT_NE(error_of("name = \"d\"\nshape = \"tube\"\npoints_m = [[0.0, 0.0, 0.0], [0.01, 0.0, 0.0]]\nradius_m = 0.01\n"
                     "rgb = [1, 2, 1]\n")
                .find("rgb: each component must be in [0, 1]"),
            std::string::npos);
}

}  // namespace
}  // namespace vesica::app

namespace vesica::app {
namespace {

// Calot's triangle as data (issue 36): the variant's tubes, their holds and planned cuts.
class CalotTriangleScenarioTest : public ScenarioLoaderTest {
 protected:
  static std::string Triangle(const std::string& extra_duct_keys = "") {
    return std::string(R"(
[calot_triangle]
variant = "short cystic duct"
neck_m = [-0.017, -0.017, 0.048]

[[calot_triangle.tubes]]
name = "cystic duct"
kind = "cystic_duct"
points_m = [[-0.003, -0.063, 0.027], [-0.013, -0.041, 0.037], [-0.017, -0.017, 0.048]]
planned_cut_s = 0.55
)") + extra_duct_keys + R"(
[[calot_triangle.tubes]]
name = "cystic artery"
kind = "cystic_artery"
points_m = [[0.017, -0.037, 0.053], [-0.020, -0.015, 0.045]]
outer_radius_m = 0.0008

[[calot_triangle.tubes]]
name = "common bile duct"
kind = "common_bile_duct"
points_m = [[-0.003, -0.063, 0.027], [-0.009, -0.098, -0.007]]
)";
  }
  std::string ErrorOf(const std::string& triangle) {
    try {
      Parse(std::string(kValid) + triangle);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "no error";
  }
};

TEST_F(CalotTriangleScenarioTest, TheTubesTheirHoldsAndPlannedCutsAreRead) {
  EXPECT_FALSE(Parse(kValid).calot_triangle.has_value());  // optional
  const Scenario s = Parse(std::string(kValid) + Triangle());
  ASSERT_TRUE(s.calot_triangle.has_value());
  const CalotTriangleConfig& c = *s.calot_triangle;
  EXPECT_EQ(c.variant, "short cystic duct");
  ASSERT_EQ(c.tubes.size(), 3u);
  EXPECT_EQ(c.tubes[0].kind, physics::calot::TubeKind::kCysticDuct);
  EXPECT_EQ(c.tubes[0].end, physics::calot::TubeEndHold::kNeck);  // a cystic structure's default
  EXPECT_DOUBLE_EQ(c.tubes[0].planned_cut_s, 0.55);
  EXPECT_DOUBLE_EQ(c.tubes[1].planned_cut_s, 0.6);  // the default
  EXPECT_EQ(c.tubes[2].end, physics::calot::TubeEndHold::kClamped);  // a common duct's
  EXPECT_EQ(c.tubes[0].source, "case.toml:" + std::to_string(std::count(kValid, kValid + std::strlen(kValid), '\n') + 6));
  const physics::calot::TriangleDescription d = ToPhysics(c);
  ASSERT_EQ(d.tubes.size(), 3u);
  EXPECT_TRUE(d.p_Neck_W_m.isApprox(Eigen::Vector3d(-0.017, -0.017, 0.048)));
  EXPECT_DOUBLE_EQ(d.tubes[1].material.outer_radius_m, 0.0008);
  EXPECT_DOUBLE_EQ(d.tubes[0].material.outer_radius_m,
                   physics::calot::DefaultTubeMaterial(physics::calot::TubeKind::kCysticDuct).outer_radius_m);
  EXPECT_FALSE(d.tubes[1].end_pressurised);  // the artery bleeds from the patient's side only
  EXPECT_TRUE(d.tubes[0].end_pressurised);   // the gallbladder's bile
}

TEST_F(CalotTriangleScenarioTest, ABadTriangleIsNamed) {
  std::string text = Triangle();
  text.replace(text.find("planned_cut_s = 0.55"), 20, "planned_cut_s = 1.5");
  EXPECT_THAT(ErrorOf(text), HasSubstr("calot_triangle.tubes[0].planned_cut_s: must be in (0, 1), got 1.5"));
  text = Triangle();
  text.replace(text.find("kind = \"cystic_artery\""), 22, "kind = \"hepatic_vein\"");
  EXPECT_THAT(ErrorOf(text), HasSubstr("unknown value 'hepatic_vein'"));
  text = Triangle();
  text.replace(text.find("[-0.017, -0.017, 0.048]]"), 24, "[-0.047, -0.017, 0.048]]");
  EXPECT_THAT(ErrorOf(text), HasSubstr("calot_triangle.tubes[0].points_m: its last point is 30 mm from neck_m"));
  text = Triangle();
  text.replace(text.find("kind = \"common_bile_duct\""), 25, "kind = \"common_hepatic_duct\"");
  EXPECT_THAT(ErrorOf(text), HasSubstr("needs exactly one cystic_duct and one common_bile_duct, got 1 and 0"));
  EXPECT_THAT(ErrorOf(Triangle("colour = \"green\"\n")), HasSubstr("calot_triangle.tubes[0].colour: unknown key"));
  text = Triangle();
  text.replace(text.find("outer_radius_m = 0.0008"), 23, "outer_radius_m = 0.05");
  EXPECT_THAT(ErrorOf(text), HasSubstr("outer_radius_m: must be in"));
  text = Triangle();
  text.replace(text.find("[0.017, -0.037, 0.053], "), 24, "[-0.020, -0.015, 0.045], ");
  EXPECT_THAT(ErrorOf(text), HasSubstr("repeats the point before it"));
}

}  // namespace
}  // namespace vesica::app
