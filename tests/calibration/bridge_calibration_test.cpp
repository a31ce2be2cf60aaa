// Acceptance of the calibration in use (issue 32), closed loop: the bridge (CanArm) and a seeded
// random emulated arm on the virtual bus. The arm is calibrated with the real procedures
// (ArmCalibrator), then a hand holds the instrument and moves it slowly through poses over the
// workspace while the bridge renders a constant tip force; the force the plant pushes into the hand
// is measured against the command. Calibrated: within 5 % at every pose, and with the torque
// constants corrected by the reference-load check (protocol 1.3) within kCorrectedBound. The same
// arm with its offsets, its friction or its gravity compensation wrong: measurably not; without
// the torque-constant correction: the error of before the correction was stored. And an arm that was
// never calibrated is refused, its line naming the arm and the command to run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "device/arm_supervisor.h"
#include "device/calibration/arm_calibrator.h"
#include "device/calibration/calibration_link.h"
#include "device/can_arm.h"
#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/parameter_table.h"
#include "firmware_protocol/transport/virtual_bus.h"

namespace vesica::device {
namespace {

using namespace std::chrono_literals;
namespace emu = fp::emulator;

constexpr double kBound = 0.05;  // issue 32: the commanded tip force within 5 %
// With the torque-constant correction stored and applied. Measured over seeds 1-8: worst 0.4 %
// at any pose (0.0 .. 0.4 %); without the correction worst 4.4 % (0.4 .. 4.4 %; the arms' torque
// constants up to 4.6 % off). The bound leaves the measurement a margin of almost 4.
constexpr double kCorrectedBound = 0.015;

// The commanded tip force, trocar frame, N: lateral and along the shaft, about 2 N.
const Eigen::Vector3d kForce(0.8, -0.9, 1.5);

// Poses over the workspace (yaw rad, pitch rad, insertion m), inside every random arm's soft
// range; the hand sweeps through each at constant joint speed. Two of them pitched far at a short
// insertion, where an arm's imbalance weighs most on the tip (RandomArm: 20..50 mN m at
// sin(pitch - up to 0.3 rad)).
constexpr double kPoses[][3] = {
    {0.0, 0.0, 0.13}, {0.45, 0.7, 0.08}, {-0.45, -0.7, 0.08}, {0.45, -0.4, 0.18}, {-0.45, 0.4, 0.18}};
constexpr double kSweep[3] = {0.06, 0.06, 0.012};  // +- about the pose: 0.12 rad/s, 0.024 m/s over 1 s
constexpr double kSweepS = 1.0;
constexpr double kApproachS = 1.0;
constexpr double kWindowS = 0.4;  // measured around the pose, in the sweep's middle

Eigen::Vector3d ToEigen(const emu::Vec3& v) { return {v[0], v[1], v[2]}; }

struct ClosedLoopRig {
  emu::ArmGroundTruth truth;
  fp::VirtualClock clock;
  fp::VirtualBus bus{clock};
  fp::VirtualBusEndpoint& host_ep = bus.attach("bridge");
  fp::VirtualBusEndpoint& tool_ep = bus.attach("calibration tool");
  fp::VirtualBusEndpoint& arm_ep = bus.attach("arm");
  std::unique_ptr<emu::ArmEmulator> emulator;
  std::unique_ptr<calibration::CalibrationLink> link;
  std::unique_ptr<CanArm> bridge;
  std::unique_ptr<ArmSupervisor> supervisor;
  int step = 0;

  explicit ClosedLoopRig(std::uint64_t seed) : truth(emu::RandomArm(seed)) {
    // A firm grip: the hand follows its path closely, the force it feels is what is measured.
    truth.plant.hand.stiffness_N_per_m = 2000.0;
    truth.plant.hand.damping_N_s_per_m = 20.0;
    emu::ArmEmulator::Config ec;
    ec.board.park_position = {0.0f, 0.0f, 0.135f};  // as the calibration tests: powered up elsewhere
    emulator = std::make_unique<emu::ArmEmulator>(arm_ep, truth.plant, truth.power_up, ec);
    LetGo();
    link = std::make_unique<calibration::CalibrationLink>(tool_ep, [this](fp::Nanoseconds t) { RunUntil(t); });
  }

  void LetGo() {
    emu::HandTarget let_go;
    let_go.holding = false;
    emulator->plant().SetHandScript(emu::HandScript(let_go));
  }
  /// Bus time advances in 100 us steps; the bridge (when there is one) ticks every 1 ms.
  void RunUntil(fp::Nanoseconds t) {
    while (clock.now() < t) {
      bus.advance(100us);
      emulator->RunUntil(clock.now());
      if (++step % 10 == 0 && bridge) {
        bridge->Tick();
        if (supervisor) supervisor->Tick(clock.now());
      }
    }
  }
  void Run(double seconds, const std::function<void()>& each_step = {}) {
    const auto steps = static_cast<long>(std::lround(seconds / 1e-4));
    for (long i = 0; i < steps; ++i) {
      RunUntil(clock.now() + 100us);
      if (each_step) each_step();
    }
  }
  /// A fresh bridge for the node (as the trainer opens it), run until it reports.
  void Connect() {
    bridge = std::make_unique<CanArm>(host_ep, CanArmConfig{});
    ArmSupervisorConfig sc;
    sc.name = "left arm";
    supervisor = std::make_unique<ArmSupervisor>(*bridge, sc);
    ASSERT_EQ(bridge->Open(), DeviceStatus::kConnecting);
    Run(0.3);
  }
  void Disconnect() {
    bridge->Close();
    Run(0.01);
    supervisor.reset();
    bridge.reset();
  }
};

/// The tip target of a joint-space pose.
emu::Vec3 Tip(double yaw, double pitch, double insertion) { return emu::TipPosition({yaw, pitch, 0.0, insertion}); }

/// The hand takes the instrument where it is and, for each pose, goes to the start of its sweep
/// and sweeps through it at constant joint speed; the bridge renders kForce all along. Returns
/// the relative error |felt - commanded| / |commanded| of the mean felt force around each pose.
std::vector<double> RenderOverTheWorkspace(ClosedLoopRig& rig) {
  emu::ArmPlant& plant = rig.emulator->plant();
  const double t0 = plant.time_s();
  emu::HandScript script;
  emu::HandTarget target;
  target.p_T = emu::TipPosition(plant.q());
  script.Add(t0, target);
  double t = t0 + 0.2;
  script.Add(t, target);
  std::vector<double> window_start;
  for (const auto& pose : kPoses) {
    const double start[3] = {pose[0] - kSweep[0], pose[1] - kSweep[1], pose[2] - kSweep[2]};
    t += kApproachS;
    target.p_T = Tip(start[0], start[1], start[2]);
    script.Add(t, target);
    t += 0.3;  // settle at the start
    script.Add(t, target);
    // The sweep, keyframed every 10 ms along the joint-space line (straight in joint space).
    const int n = static_cast<int>(kSweepS / 0.01);
    for (int k = 1; k <= n; ++k) {
      const double s = static_cast<double>(k) / n;
      target.p_T = Tip(start[0] + 2 * kSweep[0] * s, start[1] + 2 * kSweep[1] * s, start[2] + 2 * kSweep[2] * s);
      script.Add(t + kSweepS * s, target);
    }
    window_start.push_back(t + 0.5 * (kSweepS - kWindowS));
    t += kSweepS;
  }
  plant.SetHandScript(script);
  EXPECT_EQ(rig.bridge->SetTipForce(kForce), DeviceStatus::kOk);

  std::vector<Eigen::Vector3d> sum(window_start.size(), Eigen::Vector3d::Zero());
  std::vector<int> count(window_start.size(), 0);
  rig.Run(t - t0 + 0.1, [&] {
    const double now = plant.time_s();
    for (std::size_t i = 0; i < window_start.size(); ++i) {
      if (now >= window_start[i] && now < window_start[i] + kWindowS) {
        sum[i] += ToEigen(plant.ForceOnHand());
        ++count[i];
      }
    }
  });
  EXPECT_EQ(rig.bridge->Status(), DeviceStatus::kOk) << rig.supervisor->Report().text;
  rig.bridge->SetTipForce(Eigen::Vector3d::Zero());
  rig.Run(0.1);
  std::vector<double> error;
  for (std::size_t i = 0; i < sum.size(); ++i) {
    EXPECT_GT(count[i], 0);
    const Eigen::Vector3d felt = sum[i] / std::max(count[i], 1);
    error.push_back((felt - kForce).norm() / kForce.norm());
  }
  return error;
}

double Worst(const std::vector<double>& e) { return *std::max_element(e.begin(), e.end()); }

std::string Percent(const std::vector<double>& e) {
  std::string s;
  for (double x : e) {
    char b[16];
    std::snprintf(b, sizeof b, " %.1f", 100.0 * x);
    s += b;
  }
  return s + " %";
}

class BridgeCalibrationAcceptance : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(BridgeCalibrationAcceptance, CalibratedArmRendersTheForceAndEachWrongTermShows) {
  const std::uint64_t seed = GetParam();
  ClosedLoopRig rig(seed);
  calibration::CalibrationPlan plan;
  plan.date_s = 1'790'000'000;
  const calibration::CalibrationResult r = calibration::ArmCalibrator(*rig.link, plan).Run();
  ASSERT_TRUE(r.saved) << r.failed_step << ": " << r.message;
  // The torque-constant check against the reference load, clamped on for it alone; protocol 1.3
  // stores the correction it measured.
  rig.emulator->plant().SetReferenceLoad(emu::StandardReferenceLoad());
  calibration::CalibrationPlan check = plan;
  check.steps = calibration::kStepTorqueConstant;
  const calibration::CalibrationResult kt = calibration::ArmCalibrator(*rig.link, check).Run();
  ASSERT_TRUE(kt.saved) << kt.failed_step << ": " << kt.message;
  EXPECT_TRUE(kt.not_stored.empty()) << kt.not_stored;
  rig.emulator->plant().SetReferenceLoad(emu::ReferenceLoad{});
  rig.emulator->Reboot();  // the node boots what was stored
  rig.Run(0.05);

  // Calibrated: the bridge runs on the stored calibration.
  rig.Connect();
  ASSERT_EQ(rig.bridge->Status(), DeviceStatus::kOk) << rig.supervisor->Report().text;
  EXPECT_NEAR(rig.bridge->calibration().coulomb[2], r.joint[2].coulomb, 1e-6);
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(rig.bridge->calibration().torque_constant_correction[j], kt.joint[j].torque_constant_ratio, 1e-6);
  const std::vector<double> calibrated = RenderOverTheWorkspace(rig);
  std::printf(
      "seed %llu calibrated, torque constants corrected: error per pose%s (torque constants %+.1f %+.1f "
      "%+.1f %% off)\n",
      static_cast<unsigned long long>(seed), Percent(calibrated).c_str(),
      100 * (rig.truth.torque_constant_ratio(0, 0.0302) - 1), 100 * (rig.truth.torque_constant_ratio(1, 0.0302) - 1),
      100 * (rig.truth.torque_constant_ratio(2, 0.0276) - 1));
  EXPECT_LE(Worst(calibrated), kCorrectedBound) << "calibrated arm: error per pose" << Percent(calibrated);
  rig.Disconnect();

  // The same arm with one term wrong: written into the node's parameters (not saved) before the
  // bridge connects, so the bridge reads or the node applies the wrong value.
  struct Wrong {
    const char* what;
    std::vector<std::pair<std::uint16_t, float>> writes;
  };
  auto stored = [&](std::uint16_t index) { return rig.emulator->node().parameters().f32(index); };
  const Wrong wrongs[] = {
      {"offsets (yaw +0.1 rad, pitch -0.1 rad, insertion +10 mm)",
       {{fp::param::kPositionOffset + 0, stored(fp::param::kPositionOffset + 0) + 0.1f},
        {fp::param::kPositionOffset + 1, stored(fp::param::kPositionOffset + 1) - 0.1f},
        {fp::param::kPositionOffset + 2, stored(fp::param::kPositionOffset + 2) + 0.01f}}},
      {"friction (none compensated)",
       {{fp::param::kCoulombFriction + 0, 0.0f},
        {fp::param::kCoulombFriction + 1, 0.0f},
        {fp::param::kCoulombFriction + 2, 0.0f},
        {fp::param::kViscousFriction + 0, 0.0f},
        {fp::param::kViscousFriction + 1, 0.0f},
        {fp::param::kViscousFriction + 2, 0.0f}}},
      {"gravity (not compensated)", {{fp::param::kGravitySin, 0.0f}, {fp::param::kGravityCos, 0.0f}}},
      {"torque constants (not corrected)",
       {{fp::param::kTorqueConstantCorrection + 0, 1.0f},
        {fp::param::kTorqueConstantCorrection + 1, 1.0f},
        {fp::param::kTorqueConstantCorrection + 2, 1.0f}}},
  };
  for (const Wrong& w : wrongs) {
    SCOPED_TRACE(w.what);
    rig.LetGo();
    rig.emulator->Reboot();  // the stored calibration again, then the wrong term in RAM
    rig.Run(0.05);
    rig.link->Connect();
    for (const auto& [index, value] : w.writes) rig.link->WriteF32(index, value);
    rig.Connect();
    ASSERT_EQ(rig.bridge->Status(), DeviceStatus::kOk) << rig.supervisor->Report().text;
    const std::vector<double> wrong = RenderOverTheWorkspace(rig);
    std::printf("seed %llu %s: error per pose%s\n", static_cast<unsigned long long>(seed), w.what,
                Percent(wrong).c_str());
    if (w.writes.front().first == fp::param::kTorqueConstantCorrection) {
      // As before the correction was stored: within 5 %, worse than corrected.
      EXPECT_LE(Worst(wrong), kBound) << "error per pose" << Percent(wrong);
      EXPECT_GT(Worst(wrong), Worst(calibrated)) << "error per pose" << Percent(wrong);
    } else {
      EXPECT_GT(Worst(wrong), kBound) << "error per pose" << Percent(wrong);
    }
    rig.Disconnect();
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, BridgeCalibrationAcceptance, ::testing::Range<std::uint64_t>(1, 9));

TEST(BridgeCalibrationTest, UncalibratedArmIsRefusedNamingTheArmAndTheCommand) {
  ClosedLoopRig rig(5);  // a random arm as built: nothing stored
  rig.Run(0.05);
  rig.Connect();
  rig.Run(1.0);
  EXPECT_EQ(rig.bridge->Status(), DeviceStatus::kNotCalibrated);
  EXPECT_FALSE(rig.emulator->node().enabled());
  EXPECT_EQ(
      rig.supervisor->Report().text,
      "left arm (node 1): no valid calibration (slot A: blank, slot B: blank); run `vesica-calibrate calibrate 1`");
  // Once calibrated (the technician ran the command), the same arm comes up.
  rig.Disconnect();
  calibration::CalibrationPlan plan;
  const calibration::CalibrationResult r = calibration::ArmCalibrator(*rig.link, plan).Run();
  ASSERT_TRUE(r.saved) << r.failed_step << ": " << r.message;
  rig.Connect();
  EXPECT_EQ(rig.bridge->Status(), DeviceStatus::kOk) << rig.supervisor->Report().text;
  EXPECT_EQ(rig.supervisor->Report().text, "left arm: ok");
}

}  // namespace
}  // namespace vesica::device
