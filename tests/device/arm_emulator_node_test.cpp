// The emulated board under the reference node: sensors reach the host, and the node's own
// calibration procedures find what the plant hides (encoder index at an unknown mounting angle).
#include <cmath>
#include <numbers>
#include <variant>

#include <gtest/gtest.h>

#include "bridge_rig.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device {
namespace {

using testing::BridgeRig;
using namespace std::chrono_literals;

TEST(ArmEmulatorNodeTest, ToolStateCarriesPoseJawPedalAndRoll) {
  BridgeRig rig;
  fp::emulator::HandTarget hand;
  hand.p_T = fp::emulator::TipPosition(BridgeRig::kStart);
  hand.jaw_rad = 0.3;
  hand.pedal = true;
  hand.roll_rad = 0.4;
  rig.emulator->plant().SetHandScript(fp::emulator::HandScript(hand));
  rig.arm->Open();
  rig.Run(0.5);
  ASSERT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  const ToolState tool = rig.arm->GetToolState();
  EXPECT_NEAR(tool.gripper_angle_rad, 0.3, 2e-3);
  EXPECT_EQ(tool.buttons & 1u, 1u);  // pedal
  const auto& q = rig.emulator->plant().q();
  EXPECT_NEAR(rig.arm->joints().roll_rad, q[2], 2e-3);
  const fp::emulator::Vec3 p = fp::emulator::TipPosition(q);
  EXPECT_LT((tool.p_BTip_B - Eigen::Vector3d(p[0], p[1], p[2])).norm(), 1e-4);
  const DeviceCapabilities& caps = rig.arm->Capabilities();
  EXPECT_EQ(caps.force_dof, 3);
  EXPECT_EQ(caps.joint_count, 4);
  EXPECT_TRUE(caps.has_gripper);
}

TEST(ArmEmulatorNodeTest, FindIndexLocatesTheEncoderIndexAtItsMountingAngle) {
  BridgeRig rig;  // host never opened: a technician's tool talks to the node instead
  fp::emulator::HandTarget let_go;
  let_go.holding = false;
  rig.emulator->plant().SetHandScript(fp::emulator::HandScript(let_go));
  fp::VirtualBusEndpoint& tool = rig.bus.attach("calibration tool");
  fp::CanFrame f;
  ASSERT_EQ(fp::encode(fp::CalibrationCommand{1, fp::CalibrationProcedure::FindIndex, 0b001, 0.1f}, f),
            fp::EncodeError::None);
  tool.send(f, rig.clock.now() + 1ms);
  bool done = false;
  rig.Run(2.0, [&] {
    fp::TimedFrame rx;
    while (tool.receive(rx)) {
      fp::Message m;
      if (fp::decode(rx.frame, m) != fp::DecodeError::None) continue;
      if (const auto* p = std::get_if<fp::CalibrationProgress>(&m); p && p->status == fp::CalibrationStatus::Done)
        done = true;
    }
  });
  ASSERT_TRUE(done);
  // Where the yaw index really is: first index edge above the power-up motor angle.
  const auto& params = rig.emulator->plant().parameters();
  const double ratio = params.motor[0].transmission_ratio;
  const double index = params.encoder[0].index_angle_rad;
  const double two_pi = 2.0 * std::numbers::pi;
  const double motor0 = BridgeRig::kStart[0] * ratio;
  const double edge = index + two_pi * std::ceil((motor0 - index) / two_pi);
  const double q_index = edge / ratio;
  const float offset = rig.emulator->node().parameters().f32(fp::param::kPositionOffset + 0);
  EXPECT_NEAR(-offset, q_index, 1e-3);  // the index becomes the joint's zero
}

TEST(ArmEmulatorNodeTest, CurrentOffsetCalibrationMeasuresTheSensorOffsets) {
  // A rig whose plant has current-sensor offsets; the node zeroes its output and averages.
  BridgeRig rig;
  fp::emulator::ArmPlantParameters params = fp::emulator::ArmPlantParameters::Nominal();
  params.current_sensor_offset_A = {0.031, -0.017, 0.052};
  fp::emulator::ArmEmulator::Config ec;
  ec.board.park_position = {0.2f, -0.1f, 0.12f};
  fp::VirtualBusEndpoint& arm2 = rig.bus.attach("arm with offsets");
  rig.emulator = std::make_unique<fp::emulator::ArmEmulator>(arm2, params, BridgeRig::kStart, ec);
  fp::VirtualBusEndpoint& tool = rig.bus.attach("calibration tool");
  fp::CanFrame f;
  fp::encode(fp::CalibrationCommand{1, fp::CalibrationProcedure::CurrentOffset, 0b111, 0.0f}, f);
  tool.send(f, rig.clock.now() + 1ms);
  rig.Run(0.2);
  ASSERT_EQ(rig.emulator->node().calibration_status(), fp::CalibrationStatus::Done);
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(rig.emulator->node().parameters().f32(fp::param::kCurrentOffset + j),
                params.current_sensor_offset_A[j], 1e-6);
}

}  // namespace
}  // namespace vesica::device
