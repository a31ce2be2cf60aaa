// The bridge and the arm's calibration on the virtual bus (deterministic, bus clock only): the
// calibration in force is read at connect and its compensation used; an arm without a valid
// calibration is never enabled and its status line says which arm and what to run; once the
// arm is calibrated the bridge notices by itself.
#include <gtest/gtest.h>

#include "bridge_rig.h"
#include "device/arm_supervisor.h"
#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device {
namespace {

using testing::BridgeRig;
using namespace std::chrono_literals;
namespace emu = fp::emulator;

emu::ArmPlantParameters Uncalibrated() {
  emu::ArmPlantParameters p = emu::ArmPlantParameters::Nominal();
  p.factory_calibrated = false;
  return p;
}

std::unique_ptr<ArmSupervisor> Supervise(CanArm& arm, const std::string& name) {
  ArmSupervisorConfig sc;
  sc.name = name;
  return std::make_unique<ArmSupervisor>(arm, sc);
}

TEST(CanArmCalibrationTest, NominalArmRunsOnItsFactoryCalibration) {
  BridgeRig rig;
  rig.arm->Open();
  rig.Run(0.2);
  ASSERT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  ASSERT_TRUE(rig.arm->calibration_valid());
  EXPECT_EQ(rig.arm->calibration_problem(), "");
  // The nominal plant's friction at the joint: motor Coulomb 0.3 mN m and viscous 1e-6 N m s/rad
  // through 14:1 (yaw, pitch); 0.4 mN m and 2e-6 through the 10 mm capstan (insertion).
  const ArmCalibration c = rig.arm->calibration();
  EXPECT_NEAR(c.coulomb[0], 14 * 0.3e-3, 1e-9);
  EXPECT_NEAR(c.viscous[1], 14 * 14 * 1e-6, 1e-9);
  EXPECT_NEAR(c.coulomb[2], 100 * 0.4e-3, 1e-8);
  EXPECT_NEAR(c.viscous[2], 100 * 100 * 2e-6, 1e-8);
  EXPECT_EQ(c.gravity_sin, 0.0);  // balanced
  EXPECT_NEAR(c.effort_per_amp[0], 0.0302 * 14, 1e-6);
  EXPECT_NEAR(c.effort_per_amp[2], 0.0276 * 100, 1e-5);
}

TEST(CanArmCalibrationTest, UncalibratedArmIsNeverEnabledAndItsLineSaysWhatToRun) {
  BridgeRig rig({}, Uncalibrated());
  auto supervisor = Supervise(*rig.arm, "left arm");
  rig.arm->Open();
  bool ever_enabled = false;
  rig.Run(2.0, [&] {
    supervisor->Tick(rig.clock.now());
    ever_enabled = ever_enabled || rig.emulator->node().enabled();
  });
  EXPECT_FALSE(ever_enabled);
  EXPECT_EQ(rig.emulator->node().state(), fp::NodeState::PreOperational);  // never started
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kNotCalibrated);
  EXPECT_FALSE(rig.arm->calibration_valid());
  EXPECT_EQ(
      supervisor->Report().text,
      "left arm (node 1): no valid calibration (slot A: blank, slot B: blank); run `vesica-calibrate calibrate 1`");
  // A force asked for meanwhile reaches no motor.
  EXPECT_EQ(rig.arm->SetTipForce(Eigen::Vector3d(1, 0, 0)), DeviceStatus::kNotCalibrated);
  rig.Run(0.1);
  for (float a : rig.emulator->board().applied_currents()) EXPECT_EQ(a, 0.0f);
}

TEST(CanArmCalibrationTest, SettingsOnlySlotIsNoCalibrationAndTheCommandIsTheConfiguredOne) {
  // Node 2 of a board nobody calibrated: the factory stored only its node id (slot A valid).
  fp::VirtualClock clock;
  fp::VirtualBus bus(clock);
  fp::VirtualBusEndpoint& host_ep = bus.attach("host");
  fp::VirtualBusEndpoint& arm_ep = bus.attach("arm");
  emu::ArmEmulator::Config ec;
  ec.node_id = 2;
  emu::ArmEmulator arm(arm_ep, Uncalibrated(), BridgeRig::kStart, ec);
  ASSERT_EQ(arm.node().active_slot(), 0);
  CanArmConfig config;
  config.node_id = 2;
  CanArm host(host_ep, config);
  ArmSupervisorConfig sc;
  sc.name = "right arm";
  sc.calibrate_command = "vesica-calibrate --can can0 calibrate right";
  ArmSupervisor supervisor(host, sc);
  host.Open();
  for (int ms = 0; ms < 500; ++ms) {
    for (int k = 0; k < 10; ++k) {
      bus.advance(100us);
      arm.RunUntil(clock.now());
    }
    host.Tick();
    supervisor.Tick(clock.now());
  }
  EXPECT_FALSE(arm.node().enabled());
  EXPECT_EQ(supervisor.Report().text,
            "right arm (node 2): no valid calibration (slot A holds settings only, written by no calibration); run "
            "`vesica-calibrate --can can0 calibrate right`");
}

TEST(CanArmCalibrationTest, ArmCalibratedWhileRefusedComesUpByItself) {
  CanArmConfig config;
  config.calibration_recheck = 500ms;
  BridgeRig rig(config, Uncalibrated());
  rig.arm->Open();
  rig.Run(0.3);
  ASSERT_EQ(rig.arm->Status(), DeviceStatus::kNotCalibrated);
  // A technician's tool stores a calibration (here: the defaults, saved by a tool of version
  // 0.1.0) while the bridge keeps the link.
  fp::VirtualBusEndpoint& tool = rig.bus.attach("calibration tool");
  auto send = [&](const fp::Message& m) {
    fp::CanFrame f;
    ASSERT_EQ(fp::encode(m, f), fp::EncodeError::None);
    ASSERT_EQ(tool.send(f, rig.clock.now() + 5ms), fp::SendStatus::Queued);
    rig.Run(0.005);
  };
  send(fp::ParameterRequest{1, fp::ParameterOp::Write, fp::ParameterType::U32, fp::param::kCalibrationToolVersion,
                            0x000100});
  send(fp::ParameterRequest{1, fp::ParameterOp::Save, fp::ParameterType::None, 0, 0});
  ASSERT_EQ(rig.emulator->node().active_slot(), 0);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kNotCalibrated);  // not read again yet
  rig.Run(0.8);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  EXPECT_TRUE(rig.emulator->node().enabled());
}

}  // namespace
}  // namespace vesica::device
