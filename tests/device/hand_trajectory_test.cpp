// vesica-armsim's scripted hands: the figure eight, the recorded hand (a recorded pose becomes the
// tip target the trainer measures back as the same pose), and an emulated arm following them.
#include "app/armsim/hand_trajectory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "app/session/arm_input.h"
#include "bridge_rig.h"
#include "device/input/input_recording.h"

namespace vesica::app {
namespace {

using namespace std::chrono_literals;

/// A haptic device that reports a fixed tool state: what ArmInput turns into a pose.
class StillArm final : public device::HapticDevice {
 public:
  device::DeviceStatus Open() override { return device::DeviceStatus::kOk; }
  void Close() override {}
  const device::DeviceCapabilities& Capabilities() const override { return caps_; }
  device::DeviceStatus Status() const override { return device::DeviceStatus::kOk; }
  device::JointState GetJointState() const override { return joints_; }
  device::ToolState GetToolState() const override { return tool_; }
  device::DeviceStatus SetTipForce(const Eigen::Vector3d&) override { return device::DeviceStatus::kOk; }
  device::DeviceStatus ResetFault() override { return device::DeviceStatus::kOk; }
  void Set(const emu::Vec3& p_T, double roll_rad, double jaw_rad, bool pedal) {
    tool_.p_BTip_B = {p_T[0], p_T[1], p_T[2]};
    tool_.gripper_angle_rad = jaw_rad;
    tool_.buttons = pedal ? 1u : 0u;
    joints_.count = 4;
    joints_.position[2] = roll_rad;
  }

 private:
  device::DeviceCapabilities caps_;
  device::ToolState tool_;
  device::JointState joints_;
};

double Elevation(const Eigen::Vector3d& d) { return std::asin(d.normalized().z()); }

// The armsim's recorded hand must put the tip where the trainer, reading the arm, sees the
// recorded pose again: TipInTrocarFrame inverts ArmInput's mapping for any reference direction
// (the azimuth drops out), so the instrument in the trainer follows the recording.
TEST(HandTrajectoryTest, RecordedPoseComesBackFromTheTrainersArmInput) {
  const Eigen::Vector3d rc(-0.085, 0.109881, 0.05);
  for (const Eigen::Vector3d& reference :
       {Eigen::Vector3d(0.044362, -0.096238, -0.028821), Eigen::Vector3d(-0.050638, -0.115493, 0.021179),
        Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(0.3, 0.2, -0.9)}) {
    const physics::InstrumentMount mount{physics::InstrumentRole::kGrasper, rc, reference.normalized()};
    StillArm arm;
    ArmInput input({&arm, nullptr}, {mount, mount});
    for (const auto& [yaw, pitch, insertion] :
         {std::array{0.0, 0.0, 0.05}, std::array{0.3, -0.2, 0.12}, std::array{-0.5, 0.4, 0.09}}) {
      physics::InstrumentPose pose;
      pose.yaw_rad = yaw;
      pose.pitch_rad = pitch;
      pose.insertion_m = insertion;
      arm.Set(TipInTrocarFrame(pose, Elevation(reference)), 0.2, 0.4, true);
      const device::InstrumentInput got = input.Sample(0.0).instruments[0];
      EXPECT_NEAR(got.pose.yaw_rad, yaw, 1e-9) << reference.transpose();
      EXPECT_NEAR(got.pose.pitch_rad, pitch, 1e-9) << reference.transpose();
      EXPECT_NEAR(got.pose.insertion_m, insertion, 1e-12);
      EXPECT_DOUBLE_EQ(got.pose.roll_rad, 0.2);
      EXPECT_DOUBLE_EQ(got.pose.jaw_angle_rad, 0.4);
      EXPECT_TRUE(got.pedal);
    }
  }
}

TEST(HandTrajectoryTest, FigureEightStartsAtTheCentreAndRepeats) {
  const emu::Vec3 centre{0.01, -0.02, 0.12};
  const emu::HandScript s = FigureEightHand(centre, 0.025, 6.0);
  const emu::HandTarget at0 = s.At(0.0);
  EXPECT_NEAR(at0.p_T[0], centre[0], 1e-12);
  EXPECT_NEAR(at0.p_T[1], centre[1], 1e-12);
  EXPECT_NEAR(at0.p_T[2], centre[2], 1e-12);
  const emu::HandTarget quarter = s.At(1.5);  // phase pi/2: furthest to +x, back on the y centre
  EXPECT_NEAR(quarter.p_T[0], centre[0] + 0.025, 1e-12);
  EXPECT_NEAR(quarter.p_T[1], centre[1], 1e-12);
  EXPECT_NEAR(s.At(3.0).jaw_rad, 0.5, 1e-12);  // jaws fully open half way round
  for (double t : {0.7, 2.2, 4.9})
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.At(t + 6.0 * 7).p_T[k], s.At(t).p_T[k], 1e-9) << t;
  EXPECT_THROW(FigureEightHand(centre, 0.0, 6.0), std::invalid_argument);
  EXPECT_THROW(FigureEightHand(centre, 0.02, std::nan("")), std::invalid_argument);
}

TEST(HandTrajectoryTest, RecordedHandLeadsInPlaysReturnsAndRepeats) {
  const device::InputRecording rec = device::ReadInputRecording(VESICA_SOURCE_DIR "/data/recordings/dissection.csv");
  const double e0 = -0.2655;
  const emu::Vec3 start{0.0, 0.0, 0.12};
  const emu::HandScript s = RecordedHand(rec, device::kRight, e0, start, 2.0);
  const double length_s = rec.frames.back().time_s - rec.frames.front().time_s;
  EXPECT_NEAR(s.end_s(), 2.0 + length_s + 1e-3 + 2.0, 1e-9);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(s.At(0.0).p_T[k], start[k]);
  // Every recorded frame is played at its own time after the lead-in, and again one cycle later.
  const double cycle_s = s.end_s() - 2.0;
  for (std::size_t i : {std::size_t{0}, rec.frames.size() / 3, rec.frames.size() - 1}) {
    const device::InstrumentInput& in = rec.frames[i].instruments[device::kRight];
    const double t = 2.0 + rec.frames[i].time_s - rec.frames.front().time_s;
    const emu::Vec3 want = TipInTrocarFrame(in.pose, e0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(s.At(t).p_T[k], want[k], 1e-12) << "frame " << i;
      EXPECT_NEAR(s.At(t + cycle_s).p_T[k], want[k], 1e-9) << "frame " << i << ", second cycle";
    }
    EXPECT_EQ(s.At(t).pedal, in.pedal);
    EXPECT_DOUBLE_EQ(s.At(t).jaw_rad, in.pose.jaw_angle_rad);
  }
  EXPECT_THROW(RecordedHand(device::InputRecording{}, device::kLeft, e0, start), std::invalid_argument);
  EXPECT_THROW(RecordedHand(rec, 2, e0, start), std::invalid_argument);
  EXPECT_THROW(RecordedHand(rec, device::kLeft, 1.6, start), std::invalid_argument);
}

// The emulated arm, held by the figure-eight hand and enabled by the bridge (zero force asked),
// moves: the joint states the bridge reads trace the figure within a few millimetres.
TEST(HandTrajectoryTest, EmulatedArmFollowsTheFigureEightTheBridgeMeasures) {
  device::testing::BridgeRig rig;
  const emu::Vec3 centre = emu::TipPosition(device::testing::BridgeRig::kStart);
  rig.emulator->plant().SetHandScript(FigureEightHand(centre, 0.025, 4.0));
  rig.arm->Open();
  double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9, worst_lag_m = 0.0;
  int samples = 0;
  rig.Run(6.0, [&] {
    if (rig.emulator->plant().time_s() < 2.0 || ++samples % 50 != 0) return;
    const Eigen::Vector3d p = rig.arm->GetToolState().p_BTip_B;
    min_x = std::min(min_x, p.x());
    max_x = std::max(max_x, p.x());
    min_y = std::min(min_y, p.y());
    max_y = std::max(max_y, p.y());
    const emu::Vec3 want = rig.emulator->plant().CurrentHandTarget().p_T;
    worst_lag_m = std::max(worst_lag_m, (p - Eigen::Vector3d(want[0], want[1], want[2])).norm());
  });
  EXPECT_EQ(rig.arm->Status(), device::DeviceStatus::kOk);
  EXPECT_GT(max_x - min_x, 0.045);  // 2 x 25 mm, less the hand's lag
  EXPECT_GT(max_y - min_y, 0.02);   // 2 x 12.5 mm
  EXPECT_LT(worst_lag_m, 0.005);
}

}  // namespace
}  // namespace vesica::app
