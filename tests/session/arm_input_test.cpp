// Haptic arms as the instruments' input: the measured tip becomes the pose, the rendered force
// goes back to the arm in its trocar frame, and a hook pushed into the liver feels it push back.

#include "app/session/arm_input.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <thread>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "app/session/session_runner.h"
#include "physics/collision/surface_ray_caster.h"

namespace vesica::app {
namespace {

using namespace std::chrono_literals;

class FakeArm final : public device::HapticDevice {
 public:
  device::DeviceStatus Open() override { return device::DeviceStatus::kOk; }
  void Close() override {}
  const device::DeviceCapabilities& Capabilities() const override { return caps_; }
  device::DeviceStatus Status() const override { return device::DeviceStatus::kOk; }
  device::JointState GetJointState() const override {
    std::lock_guard lock(mutex_);
    return joints_;
  }
  device::ToolState GetToolState() const override {
    std::lock_guard lock(mutex_);
    return tool_;
  }
  device::DeviceStatus SetTipForce(const Eigen::Vector3d& f) override {
    std::lock_guard lock(mutex_);
    force_ = f;
    ++force_calls_;
    return device::DeviceStatus::kOk;
  }
  device::DeviceStatus ResetFault() override { return device::DeviceStatus::kOk; }
  void Set(const Eigen::Vector3d& p_T, double gripper, bool pedal, double roll) {
    std::lock_guard lock(mutex_);
    tool_.p_BTip_B = p_T;
    tool_.gripper_angle_rad = gripper;
    tool_.buttons = pedal ? 1u : 0u;
    joints_.count = 4;
    joints_.position[2] = roll;
  }
  void SetButtons(std::uint32_t buttons) {
    std::lock_guard lock(mutex_);
    tool_.buttons = buttons;
  }
  Eigen::Vector3d force() const {
    std::lock_guard lock(mutex_);
    return force_;
  }
  long force_calls() const {
    std::lock_guard lock(mutex_);
    return force_calls_;
  }

 private:
  mutable std::mutex mutex_;
  device::DeviceCapabilities caps_;
  device::ToolState tool_;
  device::JointState joints_;
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();
  long force_calls_ = 0;
};

physics::InstrumentMount Mount(const Eigen::Vector3d& rc, const Eigen::Vector3d& dir) {
  return {physics::InstrumentRole::kGrasper, rc, dir.normalized()};
}

TEST(ArmInputTest, TrocarFrameIsARotationAlongTheReference) {
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d(0.3, -0.8, 0.2), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, -1)}) {
    const Eigen::Matrix3d r = TrocarFrame(Mount(Eigen::Vector3d::Zero(), d));
    EXPECT_TRUE((r.transpose() * r).isIdentity(1e-12));
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    EXPECT_TRUE(r.col(2).isApprox(d.normalized(), 1e-12));
  }
}

TEST(ArmInputTest, MeasuredTipBecomesThePoseAndForceGoesBackInTheTrocarFrame) {
  FakeArm left, right;
  const std::array<physics::InstrumentMount, 2> mounts{Mount({-0.08, 0.1, 0.05}, {0.4, -0.9, -0.1}),
                                                       Mount({-0.01, 0.12, 0.1}, {-0.2, -0.8, -0.6})};
  ArmInput input({&left, &right}, mounts);
  const Eigen::Vector3d p_T(0.012, -0.02, 0.09);
  left.Set(p_T, 0.4, false, 0.0);
  right.Set(Eigen::Vector3d(-0.005, 0.01, 0.07), 0.0, true, 0.3);
  const device::InputFrame f = input.Sample(1.25);
  EXPECT_EQ(f.time_s, 1.25);
  const Eigen::Matrix3d r = TrocarFrame(mounts[0]);
  const Eigen::Vector3d tip =
      physics::TipPosition(mounts[0].p_RemoteCentre_W, mounts[0].reference_direction_W, f.instruments[0].pose);
  EXPECT_TRUE(tip.isApprox(mounts[0].p_RemoteCentre_W + r * p_T, 1e-12)) << tip.transpose();
  EXPECT_EQ(f.instruments[0].pose.jaw_angle_rad, 0.4);
  EXPECT_FALSE(f.instruments[0].pedal);
  EXPECT_TRUE(f.instruments[1].pedal);
  EXPECT_EQ(f.instruments[1].pose.roll_rad, 0.3);
  Eigen::Vector3d p_W;
  ASSERT_TRUE(input.ToolPoint(0, p_W));
  EXPECT_TRUE(p_W.isApprox(tip, 1e-12));
  const Eigen::Vector3d f_W(0.5, -1.0, 2.0);
  input.SetForce(0, f_W);
  EXPECT_TRUE((r * left.force()).isApprox(f_W, 1e-12));
}

TEST(ArmInputTest, MissingArmKeepsTheFallbackPose) {
  FakeArm right;
  device::InputFrame fallback;
  fallback.instruments[0].pose.insertion_m = 0.04;
  fallback.instruments[0].pose.yaw_rad = 0.1;
  ArmInput input({nullptr, &right}, {Mount({0, 0, 0}, {0, 0, -1}), Mount({0, 0, 0}, {0, 1, 0})}, fallback);
  right.Set(Eigen::Vector3d(0, 0, 0.05), 0, false, 0);
  const device::InputFrame f = input.Sample(0);
  EXPECT_EQ(f.instruments[0].pose.insertion_m, 0.04);
  EXPECT_EQ(f.instruments[0].pose.yaw_rad, 0.1);
  Eigen::Vector3d p;
  EXPECT_FALSE(input.ToolPoint(0, p));
  input.SetForce(0, Eigen::Vector3d::Ones());  // nothing to send to: no crash
}

TEST(ArmInputTest, EachPressOfTheRightHandleButtonExchangesItsTool) {
  using physics::InstrumentTool;
  FakeArm left, right;
  ArmInput input({&left, &right}, {Mount({0, 0, 0}, {0, 0, -1}), Mount({0, 0, 0}, {0, 1, 0})}, {}, {},
                 ToolExchange({InstrumentTool::kCauteryHook, InstrumentTool::kClipApplier, InstrumentTool::kScissors}));
  right.Set(Eigen::Vector3d(0, 0, 0.05), 0, false, 0);
  EXPECT_EQ(input.Sample(0).right_tool, InstrumentTool::kCauteryHook);
  right.SetButtons(2u);  // pressed and held for three samples: one exchange
  for (int i = 1; i <= 3; ++i) EXPECT_EQ(input.Sample(0.001 * i).right_tool, InstrumentTool::kClipApplier);
  right.SetButtons(0u);
  EXPECT_EQ(input.Sample(0.004).right_tool, InstrumentTool::kClipApplier);
  right.SetButtons(3u);  // pedal and handle: the pedal still reads, the tool moves on
  const device::InputFrame f = input.Sample(0.005);
  EXPECT_EQ(f.right_tool, InstrumentTool::kScissors);
  EXPECT_TRUE(f.instruments[1].pedal);
  right.SetButtons(0u);
  input.Sample(0.006);
  right.SetButtons(2u);
  EXPECT_EQ(input.Sample(0.007).right_tool, InstrumentTool::kCauteryHook);  // round again
  right.SetButtons(0u);
  left.SetButtons(2u);  // the grasper's handle button exchanges nothing
  EXPECT_EQ(input.Sample(0.008).right_tool, InstrumentTool::kCauteryHook);
  EXPECT_FALSE(device::FrameProblem(input.Sample(0.009), nullptr).has_value());
}

TEST(ArmInputTest, HookArmPushedIntoAnOrganFeelsItPushBack) {
  const Scenario scenario = LoadScenario(DefaultScenarioPath());
  const auto model = BuildDissectionModelFor(scenario, LoadSceneMeshes(scenario));
  FakeArm grasper, hook;
  // The hook aimed at the gallbladder's centre, and where that line first meets an organ at rest.
  physics::SurfaceRayCaster organs;
  organs.AddSurface(model->liver->rest_surface);
  organs.AddSurface(model->gallbladder_boundary.surface);
  const physics::InstrumentMount& mount = model->instruments[1];
  const Eigen::Vector3d aim = model->gallbladder->rest_mesh.vertices.colwise().mean().transpose();
  const Eigen::Vector3d along_W = (aim - mount.p_RemoteCentre_W).normalized();
  const auto hit = organs.FirstHit(physics::ToolSegment{mount.p_RemoteCentre_W, aim});
  ASSERT_TRUE(hit.has_value()) << "the line to the gallbladder's centre meets an organ";
  const Eigen::Vector3d along_T = TrocarFrame(mount).transpose() * along_W;  // the arm's frame
  const double contact_m = hit->distance;
  grasper.Set(Eigen::Vector3d(0, 0, 0.04), 0.5, false, 0);
  hook.Set((contact_m - 0.027) * along_T, 0.0, false, 0);
  std::atomic<long> servo_ticks{0};
  auto arms = std::make_shared<ArmInput>(std::array<device::HapticDevice*, 2>{&grasper, &hook}, model->instruments,
                                         device::InputFrame{}, [&] { ++servo_ticks; });
  RunnerOptions options;
  options.haptic_io = arms;
  SessionRunner runner(model, DefaultCauteryParams(), arms, options);
  runner.Start();
  // From 27 mm short of the contact to 8 mm past it, slowly.
  for (int k = 0; k <= 50; ++k) {
    hook.Set((contact_m - 0.027 + k * 0.035 / 50.0) * along_T, 0.0, false, 0);
    std::this_thread::sleep_for(10ms);
  }
  // 0.3 s of session time at the deepest point (wall time would do on an idle machine only).
  const double pushed_at = runner.Status().session_time_s;
  RunnerStatus s = runner.Status();
  for (int i = 0; i < 6000 && s.error.empty() && s.session_time_s < pushed_at + 0.3; ++i) {
    std::this_thread::sleep_for(10ms);
    s = runner.Status();
  }
  EXPECT_GE(s.session_time_s, pushed_at + 0.3);
  EXPECT_TRUE(s.error.empty()) << s.error;
  EXPECT_GT(servo_ticks.load(), 100);
  EXPECT_GT(hook.force_calls(), 100);
  // The organ resists: a push back out along the shaft (a curved wall also pushes the tip
  // sideways), felt by the hook and not by the grasper.
  const Eigen::Vector3d f_T = hook.force();
  EXPECT_LT(f_T.dot(along_T), -0.01) << f_T.transpose();
  EXPECT_GT(f_T.norm(), 0.02) << f_T.transpose();
  EXPECT_EQ(grasper.force(), Eigen::Vector3d::Zero());
  runner.End();
}

}  // namespace
}  // namespace vesica::app
