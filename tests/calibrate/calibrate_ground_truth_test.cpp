// vesica-calibrate (the real program) calibrates seeded random emulated arms: the report's
// numbers are the arm's ground truth within issue 32's tolerances, what was stored is what the
// report says, the files beside it are what they claim, and the bus log reads back whole.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "app/calibrate/stored_calibration.h"
#include "firmware_protocol/buslog/bus_log_reader.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/parameter_table.h"
#include "ground_truth_checks.h"
#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

namespace emu = fp::emulator;
using testing::RunTool;
constexpr const char* kJoint[3] = {"yaw", "pitch", "insertion"};

class CalibrateGroundTruth : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(CalibrateGroundTruth, TheReportsNumbersAreTheArmsGroundTruth) {
  const std::uint64_t seed = GetParam();
  const std::string dir = testing::FreshDir("truth-" + std::to_string(seed));
  const auto run = RunTool({"--emulated", std::to_string(seed), "--dir", dir, "--json", "--yes", "--quiet", "--date",
                            "1790000000", "calibrate", "1"});
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const nlohmann::json r = run.json();
  EXPECT_TRUE(r["ok"].get<bool>());
  EXPECT_TRUE(r["saved"].get<bool>());
  EXPECT_TRUE(r["all_pass"].get<bool>());

  const emu::ArmGroundTruth t = emu::RandomArm(seed);
  testing::ExpectMeasuredIsGroundTruth(r["measured"], t);
  for (int j = 0; j < 3; ++j) {
    const auto& m = r["measured"]["joints"][kJoint[j]];
    const int dir_sign = m["direction"].get<int>();
    // What is stored now is what was measured (the float the node keeps).
    const auto& after = r["after"][kJoint[j]];
    EXPECT_EQ(after["direction"].get<int>(), dir_sign);
    EXPECT_FLOAT_EQ(static_cast<float>(after["position_offset"].get<double>()),
                    static_cast<float>(m["position_offset"].get<double>()));
    EXPECT_FLOAT_EQ(static_cast<float>(after["coulomb"].get<double>()), static_cast<float>(m["coulomb"].get<double>()));
    EXPECT_FLOAT_EQ(static_cast<float>(after["joint_min"].get<double>()),
                    static_cast<float>(m["lower_stop"].get<double>() + (j < 2 ? 0.02 : 0.002)));
    // The previous calibration was the blank board's defaults.
    EXPECT_EQ(r["before"][kJoint[j]]["coulomb"].get<double>(), 0.0);
  }

  // Every check in the report has its tolerance and passed; one per measured value.
  EXPECT_EQ(r["checks"].size(), 28u);
  for (const auto& c : r["checks"]) {
    EXPECT_TRUE(c["pass"].get<bool>()) << c.dump();
    EXPECT_LE(c["min"].get<double>(), c["value"].get<double>());
    EXPECT_GE(c["max"].get<double>(), c["value"].get<double>());
  }

  // The files: the report's JSON equals what was printed, the PNGs are PNGs, the image copy is
  // the slot the node booted (generation 1, the date given, this arm's serial).
  const std::string session = r["session_dir"].get<std::string>();
  std::ifstream report_json(session + "/" + r["files"]["report_json"].get<std::string>());
  nlohmann::json from_file = nlohmann::json::parse(report_json);
  EXPECT_EQ(from_file["measured"], r["measured"]);
  EXPECT_EQ(from_file["checks"], r["checks"]);
  for (const char* png : {"friction_png", "range_png"}) {
    const auto bytes = testing::ReadBytes(session + "/" + r["files"][png].get<std::string>());
    ASSERT_GT(bytes.size(), 1000u) << png;
    EXPECT_EQ(std::string(bytes.begin() + 1, bytes.begin() + 4), "PNG") << png;
  }
  const auto html = testing::ReadBytes(session + "/" + r["files"]["report_html"].get<std::string>());
  EXPECT_NE(std::string(html.begin(), html.end()).find("yaw.coulomb"), std::string::npos);
  const ImageFileCheck image = ReadImageFile(session + "/" + r["files"]["image_stored"].get<std::string>());
  ASSERT_EQ(image.exit_code, 0) << image.message;
  EXPECT_EQ(image.image.header.generation, 1u);
  EXPECT_EQ(image.image.header.date_s, 1790000000u);
  EXPECT_EQ(image.image.header.serial, r["node"]["serial"].get<std::uint32_t>());
  const CalibrationValues stored = ValuesOf(image.image.params);
  EXPECT_FLOAT_EQ(static_cast<float>(stored.joint[0].coulomb),
                  static_cast<float>(r["after"]["yaw"]["coulomb"].get<double>()));
  // The image copy is the node's slot byte for byte: the emulated flash holds it at slot A.
  const auto flash = testing::ReadBytes(dir + "/emulated/seed-" + std::to_string(seed) + "-arm-1.flash");
  ASSERT_GE(flash.size(), image.image.bytes.size());
  EXPECT_TRUE(std::equal(image.image.bytes.begin(), image.image.bytes.end(), flash.begin()));

  // The bus log: candump -l lines, every one read back, as many as the tool says it logged.
  std::ifstream log(r["bus_log"].get<std::string>());
  std::vector<fp::BusLogEntry> entries;
  std::string error;
  ASSERT_TRUE(fp::read_bus_log(log, entries, error)) << error;
  EXPECT_EQ(entries.size(), r["bus_log_frames"].get<std::uint64_t>());
  EXPECT_GT(entries.size(), 10000u);
}

INSTANTIATE_TEST_SUITE_P(Seeds, CalibrateGroundTruth, ::testing::Values(3u, 11u, 27u, 40u));

// The torque-constant check on its own, after a whole calibration (the emulated arm's reference
// load fixture is clamped on by the tool): each joint's ratio within 1 % of the truth, every
// check passed, and (protocol 1.3) the ratios stored as the torque-constant corrections.
TEST(CalibrateTorqueConstant, TheCheckAloneFindsEachMotorsTorqueConstantAndStoresTheCorrection) {
  constexpr std::uint64_t kSeed = 8;
  const std::string dir = testing::FreshDir("torque-constant");
  const std::vector<std::string> common = {"--emulated", std::to_string(kSeed), "--dir", dir, "--json", "--yes",
                                           "--quiet"};
  auto args = common;
  args.insert(args.end(), {"calibrate", "1"});
  ASSERT_EQ(RunTool(args).exit_code, 0);
  const auto flash_before = testing::ReadBytes(dir + "/emulated/seed-" + std::to_string(kSeed) + "-arm-1.flash");
  args = common;
  args.insert(args.end(), {"calibrate", "1", "--step", "torque-constant"});
  const auto run = RunTool(args);
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const nlohmann::json r = run.json();
  EXPECT_TRUE(r["saved"].get<bool>());
  ASSERT_EQ(r["checks"].size(), 3u);
  for (const auto& c : r["checks"]) EXPECT_TRUE(c["pass"].get<bool>()) << c.dump();
  const emu::ArmGroundTruth t = emu::RandomArm(kSeed);
  for (int j = 0; j < 3; ++j) {
    const double truth = t.torque_constant_ratio(
        j, fp::find_parameter(static_cast<std::uint16_t>(fp::param::kTorqueConstant + j))->default_value);
    EXPECT_NEAR(r["measured"]["joints"][kJoint[j]]["torque_constant_ratio"].get<double>(), truth, 0.01 * truth);
    EXPECT_EQ(r["measured"]["joints"][kJoint[j]]["load_holds"].size(), 5u);
  }
  EXPECT_NE(testing::ReadBytes(dir + "/emulated/seed-" + std::to_string(kSeed) + "-arm-1.flash"), flash_before);
  args = common;
  args.insert(args.end(), {"info", "1"});
  const auto info = RunTool(args);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(info.json()["calibration"][kJoint[j]]["torque_constant_correction"].get<double>(),
                r["measured"]["joints"][kJoint[j]]["torque_constant_ratio"].get<double>(), 1e-6);
  EXPECT_EQ(info.json()["node"]["image_layout"], 2);
}

}  // namespace
}  // namespace vesica::app::calibrate
