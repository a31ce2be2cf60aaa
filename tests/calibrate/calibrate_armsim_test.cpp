// vesica-calibrate against vesica-armsim processes over UDP, as a technician meets the trainer's
// emulated arms: scan finds both with identity, versions, state, faults and slots; info reads
// one; the bus log of the session reads back frame for frame. A whole calibration in real time
// over UDP finds the random arm's ground truth, the session's watchdog holding on a busy host.
// With vesica-armsim --fixture-control the torque-constant check against the reference load and
// the guided hand steps run over UDP too, and protocol 1.3 stores what they measured.
#include <gtest/gtest.h>
#include <sched.h>

#include <fstream>
#include <thread>

#include "../device/armsim_process.h"
#include "app/calibrate/exit_codes.h"
#include "firmware_protocol/buslog/bus_log_reader.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/emulator/hand_sensors.h"
#include "fixture_session.h"
#include "ground_truth_checks.h"
#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

using testing::RunTool;
using testing::ToolRun;

TEST(CalibrateArmsim, ScanFindsBothArmsWithIdentityVersionsStateFaultsAndSlots) {
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  device::testing::ArmsimProcess left, right;
  ASSERT_TRUE(left.Start(VESICA_ARMSIM_PATH, {"--node-id", "1", "--local-port", std::to_string(base), "--random-arm",
                                              "9", "--log-level", "warn"}));
  ASSERT_TRUE(right.Start(VESICA_ARMSIM_PATH,
                          {"--node-id", "2", "--local-port", std::to_string(base + 2), "--log-level", "warn"}));
  const std::string dir = testing::FreshDir("armsim-scan");
  // The arms boot within a moment; scan until both answer (each try is a whole scan).
  testing::ToolRun run;
  for (int attempt = 0; attempt < 20; ++attempt) {
    run = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "--json", "scan"});
    if (run.exit_code == 0 && run.json()["arms"][1]["found"].get<bool>() && run.json()["arms"][0]["found"].get<bool>())
      break;
  }
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  const nlohmann::json j = run.json();
  EXPECT_EQ(j["bus"], "UDP 127.0.0.1:" + std::to_string(base));
  ASSERT_EQ(j["arms"].size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const nlohmann::json& a = j["arms"][k];
    EXPECT_TRUE(a["found"].get<bool>());
    EXPECT_EQ(a["arm"], k + 1);
    EXPECT_EQ(a["node"], k + 1);
    EXPECT_EQ(a["serial"], 0x5E51CA01u);  // vesica-armsim's board serial
    EXPECT_EQ(a["firmware_version"], "1.0.0");
    EXPECT_EQ(a["protocol"], "1.4");
    EXPECT_EQ(a["protocol_negotiated_minor"], 4);
    EXPECT_EQ(a["state"], "pre-operational");
    EXPECT_EQ(a["latched_fault"], "none");
    EXPECT_EQ(a["fault_count"], 0);
    ASSERT_EQ(a["slots"].size(), 2u);
  }
  // A blank board (node 1) has no calibration. Node 2 leaves the factory with slot A written
  // (generation 1: its node id and the design's values, tool version 0), valid and in use, though
  // a slot that no calibration tool wrote counts as no calibration to the bridge.
  EXPECT_EQ(j["arms"][0]["active_slot"], nullptr);
  EXPECT_EQ(j["arms"][0]["slots"][0]["status"], "blank");
  EXPECT_EQ(j["arms"][0]["slots"][1]["status"], "blank");
  EXPECT_EQ(j["arms"][1]["active_slot"], "A");
  EXPECT_EQ(j["arms"][1]["slots"][0]["status"], "ok");
  EXPECT_EQ(j["arms"][1]["slots"][0]["generation"], 1);
  EXPECT_TRUE(j["arms"][1]["slots"][0]["in_use"].get<bool>());
  EXPECT_EQ(j["arms"][1]["slots"][1]["status"], "blank");

  // The human form says the same.
  const auto text = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "scan"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("arm 1 (node 1, serial 0x5E51CA01): state pre-operational\n"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("  slot A: ok, generation 1 (in use)\n"), std::string::npos) << text.out;

  // info of the right arm: its stored values (the defaults of the parameter table).
  const auto info = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "--json", "info", "right"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json i = info.json();
  EXPECT_EQ(i["arm"], 2);
  EXPECT_EQ(i["calibration"]["insertion"]["joint_max"], static_cast<double>(0.25f));
  EXPECT_EQ(i["calibration"]["yaw"]["direction"], 1);

  // The bus log of that session reads back, as many frames as the tool logged, on interface udp2.
  std::ifstream log(i["bus_log"].get<std::string>());
  std::vector<fp::BusLogEntry> entries;
  std::string error;
  ASSERT_TRUE(fp::read_bus_log(log, entries, error)) << error;
  EXPECT_EQ(entries.size(), i["bus_log_frames"].get<std::uint64_t>());
  EXPECT_GT(entries.size(), 40u);
  for (const auto& e : entries) EXPECT_EQ(e.interface, "udp2");
  left.Kill(SIGTERM);
  right.Kill(SIGTERM);
  EXPECT_EQ(left.Finish(nullptr), 0);
  EXPECT_EQ(right.Finish(nullptr), 0);
}

// Real time over UDP loopback: the tool's servo and the arm's node are processes the scheduler
// may stall. At normal priority on a busy two-core host the stalls reach 140-450 ms and the
// servo's sweeps lose their constant speed (docs/protocol.md section 11): the tool and the arm
// run at SCHED_FIFO priority, as docs/calibration.md tells a technician on a shared host. Where
// the system refuses real-time priority this test cannot say anything and is skipped (reported
// as skipped, not passed).
bool RealTimeAllowed() {
  sched_param param{};
  param.sched_priority = 1;
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) return false;
  param.sched_priority = 0;
  sched_setscheduler(0, SCHED_OTHER, &param);
  return true;
}

TEST(CalibrateArmsim, AWholeCalibrationOverUdpFindsTheGroundTruth) {
  if (!RealTimeAllowed()) GTEST_SKIP() << "SCHED_FIFO refused here (needs CAP_SYS_NICE)";
  constexpr std::uint64_t kSeed = 11;
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  device::testing::ArmsimProcess arm;
  ASSERT_TRUE(arm.Start(VESICA_ARMSIM_PATH,
                        {"--node-id", "1", "--local-port", std::to_string(base), "--random-arm", std::to_string(kSeed),
                         "--realtime-priority", "20", "--log-level", "error", "--report"}));
  const std::string dir = testing::FreshDir("armsim-calibrate");
  testing::ToolRun run;
  // The arm boots within a moment: a calibration that found no node yet is tried again. On a
  // heavily loaded host even real-time priority may leave a sweep uneven; the tool then refuses
  // the values (exit 5, nothing saved), as a technician would see, and is run again, at most twice.
  int refused = 0;
  for (int attempt = 0; attempt < 12; ++attempt) {
    run = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "--json", "--yes", "--quiet",
                   "--realtime-priority", "20", "--date", "1790000000", "calibrate", "1"});
    if (run.exit_code == kExitFailed && refused < 2) {
      ++refused;
      EXPECT_FALSE(run.json()["saved"].get<bool>());
      continue;
    }
    if (run.exit_code != kExitNoArm) break;
  }
  ASSERT_EQ(run.exit_code, kExitOk) << run.err << run.out;
  const nlohmann::json r = run.json();
  EXPECT_TRUE(r["saved"].get<bool>());
  EXPECT_TRUE(r["all_pass"].get<bool>());
  testing::ExpectMeasuredIsGroundTruth(r["measured"], fp::emulator::RandomArm(kSeed));
  // The arm went through it without a fault (a watchdog trip would have ended the calibration).
  arm.Kill(SIGTERM);
  std::string report;
  EXPECT_EQ(arm.Finish(&report), 0);
  EXPECT_NE(report.find("state=pre-operational fault=none"), std::string::npos) << report;
}

// Runs `args` until the arm answered (it boots within a moment) or refused once more than twice
// (a sweep or hold uneven on a loaded host: exit 5, nothing saved).
template <class Run>
ToolRun UntilAnswered(const Run& run) {
  ToolRun r;
  int refused = 0;
  for (int attempt = 0; attempt < 12; ++attempt) {
    r = run();
    if (r.exit_code == kExitFailed && refused < 2) {
      ++refused;
      continue;
    }
    if (r.exit_code != kExitNoArm) break;
  }
  return r;
}

TEST(CalibrateArmsim, TheReferenceLoadAndTheHandStepsRunOverUdpAndProtocol1Point3StoresThem) {
  if (!RealTimeAllowed()) GTEST_SKIP() << "SCHED_FIFO refused here (needs CAP_SYS_NICE)";
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  // The nominal arm (factory calibrated; its torque constants as its parameters say, its hand
  // sensors HandSensorModel's defaults), nobody holding it, the reference load clamped on.
  testing::FixtureArmsim arm;
  ASSERT_TRUE(arm.Start(VESICA_ARMSIM_PATH, {"--node-id", "1", "--local-port", std::to_string(base),
                                             "--realtime-priority", "20", "--log-level", "error"}));
  ASSERT_TRUE(arm.Command("let-go"));
  ASSERT_TRUE(arm.Command("reference-load on"));
  const std::string dir = testing::FreshDir("armsim-fixture");
  const std::vector<std::string> common{"--udp-base-port", std::to_string(base),  "--dir", dir,
                                        "--json",          "--realtime-priority", "20",    "--date",
                                        "1790000000"};
  auto with = [&](std::vector<std::string> tail) {
    std::vector<std::string> a = common;
    a.insert(a.end(), tail.begin(), tail.end());
    return a;
  };
  const ToolRun kt = UntilAnswered([&] {
    return RunTool(with({"--yes", "--quiet", "calibrate", "1", "--step", "torque-constant", "--joint", "pitch"}));
  });
  ASSERT_EQ(kt.exit_code, kExitOk) << kt.err << kt.out;
  EXPECT_TRUE(kt.json()["saved"].get<bool>());
  EXPECT_NEAR(kt.json()["measured"]["joints"]["pitch"]["torque_constant_ratio"].get<double>(), 1.0, 0.01);
  ASSERT_TRUE(arm.Command("reference-load off"));

  // The guided hand steps: the tool prompts, the test's hand moves the arm's handle, waits for it
  // to get there and presses Enter.
  const std::pair<const char*, const char*> moves[] = {{"roll offset (1 of 1)", "hand roll=0"},
                                                       {"jaw span (1 of 2)", "hand jaw=0"},
                                                       {"jaw span (2 of 2)", "hand jaw=0.7"},
                                                       {"pedal travel (1 of 2)", "hand pedal=0"},
                                                       {"pedal travel (2 of 2)", "hand pedal=1"}};
  bool moved = true;
  auto hand = [&](const std::string& line) -> std::string {
    for (const auto& [prompt, command] : moves) {
      if (line.find(prompt) == std::string::npos) continue;
      moved = moved && arm.Command(command);
      std::this_thread::sleep_for(std::chrono::milliseconds(900));  // 0.4 s to get there, then still
      return "\n";
    }
    return "";
  };
  for (const char* step : {"roll-offset", "jaw-span", "pedal-travel"}) {
    SCOPED_TRACE(step);
    const ToolRun r = UntilAnswered([&] {
      return testing::RunToolAnswering(with({"calibrate", "1", "--step", step}), hand);
    });
    ASSERT_EQ(r.exit_code, kExitOk) << r.err << r.out;
    EXPECT_TRUE(r.json()["saved"].get<bool>());
  }
  EXPECT_TRUE(moved);

  // Stored on the arm, image layout 2, and read back by info.
  const ToolRun info = RunTool(with({"info", "1"}));
  ASSERT_EQ(info.exit_code, kExitOk) << info.err;
  const nlohmann::json j = info.json();
  EXPECT_EQ(j["node"]["image_layout"], 2) << info.out;
  EXPECT_TRUE(j["node"]["absent_fields"].empty()) << info.out;
  const fp::emulator::HandSensorModel sensors;  // the nominal arm's
  const nlohmann::json& h = j["calibration"]["hand"];
  EXPECT_EQ(h["jaw_closed_counts"], fp::emulator::HandSensorModel::Adc(sensors.jaw_closed_counts));
  EXPECT_EQ(h["jaw_open_counts"], sensors.JawRaw(0.6));  // the handle's stop: jaw_max_rad
  EXPECT_EQ(h["pedal_released_counts"], sensors.PedalRaw(0.0));
  EXPECT_EQ(h["pedal_pressed_counts"], sensors.PedalRaw(1.0));
  EXPECT_NEAR(h["roll_sensor_offset_rad"].get<double>(), 0.0, 3 * 2 * 3.14159265 / 16384);
  EXPECT_NEAR(j["calibration"]["pitch"]["torque_constant_correction"].get<double>(), 1.0, 0.01);
}

// Version negotiation: the 1.3 tool and a node of protocol 1.2 (armsim --firmware-minor 2). The
// jaw span is measured and reported; the tool says the node cannot store it and saves nothing;
// info says protocol 1.2 and that its image is layout 1 with the layout-2 values absent.
TEST(CalibrateArmsim, ANodeOfProtocol1Point2GetsTheHandStepButNotItsStorageAndTheToolSaysSo) {
  if (!RealTimeAllowed()) GTEST_SKIP() << "SCHED_FIFO refused here (needs CAP_SYS_NICE)";
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  testing::FixtureArmsim arm;
  ASSERT_TRUE(arm.Start(VESICA_ARMSIM_PATH, {"--node-id", "1", "--local-port", std::to_string(base), "--firmware-minor",
                                             "2", "--realtime-priority", "20", "--log-level", "error"}));
  ASSERT_TRUE(arm.Command("let-go"));
  const std::string dir = testing::FreshDir("armsim-older-node");
  const std::vector<std::string> common{"--udp-base-port", std::to_string(base),  "--dir", dir,
                                        "--json",          "--realtime-priority", "20",    "--date",
                                        "1790000000"};
  auto with = [&](std::vector<std::string> tail) {
    std::vector<std::string> a = common;
    a.insert(a.end(), tail.begin(), tail.end());
    return a;
  };
  auto hand = [&](const std::string& line) -> std::string {
    const char* command = line.find("jaw span (1 of 2)") != std::string::npos   ? "hand jaw=0"
                          : line.find("jaw span (2 of 2)") != std::string::npos ? "hand jaw=0.7"
                                                                                : nullptr;
    if (!command) return "";
    EXPECT_TRUE(arm.Command(command));
    std::this_thread::sleep_for(std::chrono::milliseconds(900));
    return "\n";
  };
  const ToolRun r = UntilAnswered([&] {
    return testing::RunToolAnswering(with({"calibrate", "1", "--step", "jaw-span"}), hand);
  });
  ASSERT_EQ(r.exit_code, kExitOk) << r.err << r.out;
  EXPECT_FALSE(r.json()["saved"].get<bool>());
  const fp::emulator::HandSensorModel sensors;
  EXPECT_EQ(r.json()["measured"]["hand"]["jaw"]["open_raw"], sensors.JawRaw(0.6));  // measured and reported
  EXPECT_NE(r.err.find("node 1 speaks protocol 1.2: the torque-constant correction and the hand sensors' "
                       "calibration are measured and reported but not stored (they need 1.3; update the arm's "
                       "firmware)"),
            std::string::npos)
      << r.err;
  const ToolRun info = RunTool(with({"info", "1"}));
  ASSERT_EQ(info.exit_code, kExitOk) << info.err;
  const nlohmann::json node = info.json()["node"];
  EXPECT_EQ(node["protocol"], "1.2");
  EXPECT_EQ(node["protocol_negotiated_minor"], 2);
  EXPECT_EQ(node["image_layout"], 1);
  ASSERT_EQ(node["absent_fields"].size(), 9u);
  EXPECT_EQ(node["absent_fields"][0], "torque_constant_correction[yaw]");
}

}  // namespace
}  // namespace vesica::app::calibrate
