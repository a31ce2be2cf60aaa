// Bridge + emulator closed loop on the virtual bus (deterministic: bus clock only).
#include "device/can_arm.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "bridge_rig.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device {
namespace {

using testing::BridgeRig;
using testing::ToEigen;
using namespace std::chrono_literals;

double MaxAbs(const std::array<double, 3>& a) {
  return std::max({std::abs(a[0]), std::abs(a[1]), std::abs(a[2])});
}

TEST(CanArmTest, HandshakeReachesRunning) {
  BridgeRig rig;
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kNotOpen);
  EXPECT_EQ(rig.arm->Open(), DeviceStatus::kConnecting);
  EXPECT_EQ(rig.arm->Open(), DeviceStatus::kAlreadyOpen);
  rig.Run(0.2);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  EXPECT_EQ(rig.arm->node_state(), fp::NodeState::Operational);
  EXPECT_TRUE(rig.emulator->node().enabled());
  // The host reads the emulated arm's pose through the node's joint states.
  const ArmJoints q = rig.arm->joints();
  EXPECT_NEAR(q.yaw_rad, rig.emulator->plant().q()[0], 1e-3);
  EXPECT_NEAR(q.pitch_rad, rig.emulator->plant().q()[1], 1e-3);
  EXPECT_NEAR(q.insertion_m, rig.emulator->plant().q()[3], 1e-4);
  EXPECT_EQ(rig.arm->decode_errors().total(), 0u);
}

// Steady tip force felt by the emulated hand equals the commanded force within 5%, and the force
// the motors produce never exceeds the command (beyond 5%) nor any motor current limit.
TEST(CanArmTest, ClosedLoopSteadyTipForceMatchesCommand) {
  for (const Eigen::Vector3d& f : {Eigen::Vector3d(1.0, -0.5, 1.5), Eigen::Vector3d(-2.0, 1.0, -0.5),
                                  Eigen::Vector3d(0.0, 0.0, 3.0)}) {
    BridgeRig rig;
    rig.arm->Open();
    rig.Run(0.2);
    ASSERT_EQ(rig.arm->Status(), DeviceStatus::kOk);
    ASSERT_EQ(rig.arm->SetTipForce(f), DeviceStatus::kOk);
    const ArmActuation limits = ArmActuation::Nominal();
    const std::array<double, 3> max_A{limits.yaw.max_current_A, limits.pitch.max_current_A,
                                      limits.insertion.max_current_A};
    double worst_over = 0.0;
    bool current_over = false;
    auto check = [&] {
      const Eigen::Vector3d f_act = ToEigen(rig.emulator->plant().ActuatorTipForce());
      worst_over = std::max(worst_over, f_act.norm() - f.norm());
      const auto amps = rig.emulator->plant().motor_current_A();
      for (int m = 0; m < 3; ++m)
        if (std::abs(amps[m]) > max_A[m]) current_over = true;
    };
    rig.Run(1.5, check);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    int n = 0;
    rig.Run(0.5, [&] {
      check();
      mean += ToEigen(rig.emulator->plant().ForceOnHand());
      ++n;
    });
    mean /= n;
    EXPECT_LT((mean - f).norm(), 0.05 * f.norm()) << "commanded " << f.transpose() << " felt " << mean.transpose();
    EXPECT_LT(worst_over, 0.05 * f.norm());
    EXPECT_FALSE(current_over);
    EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::None);
  }
}

// The felt force is sensitive to the host's model: a host that believes the torque constants are
// 10% higher than they are renders 1/1.1 of the command (and the 5% check above would fail).
TEST(CanArmTest, HostTorqueConstantErrorShowsInFeltForce) {
  CanArmConfig wrong;
  for (JointActuator* a : {&wrong.actuation.yaw, &wrong.actuation.pitch, &wrong.actuation.insertion})
    a->torque_constant_Nm_per_A *= 1.1;
  BridgeRig rig(wrong);
  rig.arm->Open();
  rig.Run(0.2);
  const Eigen::Vector3d f(1.0, -0.5, 1.5);
  rig.arm->SetTipForce(f);
  rig.Run(1.5);
  const Eigen::Vector3d felt = ToEigen(rig.emulator->plant().ForceOnHand());
  EXPECT_LT((felt - f / 1.1).norm(), 0.02 * f.norm());
  EXPECT_GT((felt - f).norm(), 0.07 * f.norm());
}

TEST(CanArmTest, SaturatedForceKeepsDirectionAndStaysWithinLimits) {
  CanArmConfig config;
  BridgeRig rig(config);
  rig.arm->Open();
  rig.Run(0.2);
  const Eigen::Vector3d f(10.0, 5.0, 30.0);  // far above max_tip_force_N
  rig.arm->SetTipForce(f);
  double max_force = 0.0;
  std::array<double, 3> max_amps{};
  rig.Run(1.5, [&] {
    max_force = std::max(max_force, ToEigen(rig.emulator->plant().ActuatorTipForce()).norm());
    const auto amps = rig.emulator->plant().motor_current_A();
    for (int m = 0; m < 3; ++m) max_amps[m] = std::max(max_amps[m], std::abs(amps[m]));
  });
  const double limit = config.actuation.max_tip_force_N;
  EXPECT_LE(max_force, 1.01 * limit);
  EXPECT_LE(max_amps[0], config.actuation.yaw.max_current_A * 1.001);
  EXPECT_LE(max_amps[1], config.actuation.pitch.max_current_A * 1.001);
  EXPECT_LE(max_amps[2], config.actuation.insertion.max_current_A * 1.001);
  const Eigen::Vector3d felt = ToEigen(rig.emulator->plant().ForceOnHand());
  EXPECT_GT(felt.normalized().dot(f.normalized()), 0.99);
  EXPECT_NEAR(felt.norm(), limit, 0.05 * limit);
  EXPECT_NE(rig.arm->last_command().active_limit, ActuationLimit::kNone);
}

TEST(CanArmTest, RejectsBadInputWithNamedErrors) {
  CanArmConfig bad;
  bad.actuation.insertion.torque_constant_Nm_per_A = 0.0;
  BridgeRig rig(bad);
  EXPECT_EQ(rig.arm->Open(), DeviceStatus::kInvalidArgument);
  EXPECT_NE(rig.arm->last_error().find("insertion.torque_constant_Nm_per_A"), std::string::npos);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kNotOpen);

  // A watchdog the node would refuse (it keeps its 3 ms and trips on a loaded host).
  CanArmConfig slow_watchdog;
  slow_watchdog.node_watchdog_timeout = 150ms;
  BridgeRig refused(slow_watchdog);
  EXPECT_EQ(refused.arm->Open(), DeviceStatus::kInvalidArgument);
  EXPECT_EQ(refused.arm->last_error(),
            "CanArmConfig.node_watchdog_timeout must be 0 (keep the node's) or 500..100000 us, got 150000 us");

  BridgeRig good;
  good.arm->Open();
  good.Run(0.1);
  EXPECT_EQ(good.arm->SetTipForce(Eigen::Vector3d(NAN, 0, 0)), DeviceStatus::kInvalidArgument);
  // A garbage frame on the arm's joint-state id (wrong length) is counted, not believed.
  fp::VirtualBusEndpoint& rogue = good.bus.attach("rogue");
  fp::CanFrame junk;
  junk.id = 0x181;
  junk.len = 3;
  junk.data[0] = 0xFF;
  rogue.send(junk, good.clock.now() + 1ms);
  const ArmJoints before = good.arm->joints();
  good.Run(0.01);
  EXPECT_EQ(good.arm->decode_errors()[fp::DecodeError::WrongLength], 1u);
  EXPECT_NEAR(good.arm->joints().yaw_rad, before.yaw_rad, 1e-3);
  EXPECT_EQ(good.arm->Status(), DeviceStatus::kOk);
}

// Stop the host mid-loop: the node's watchdog must zero the motor torque within 5 ms of bus
// time and latch the fault; a restarted host sees the fault and recovers only after a reset.
TEST(CanArmTest, WatchdogZeroesTorqueLatchesFaultAndNeedsReset) {
  BridgeRig rig;
  rig.arm->Open();
  rig.Run(0.2);
  const Eigen::Vector3d f(1.0, -0.5, 1.5);
  rig.arm->SetTipForce(f);
  rig.Run(0.5);
  ASSERT_GT(MaxAbs(rig.emulator->plant().motor_current_A()), 0.1);

  rig.host_running = false;  // the host process hangs
  const double stopped_at = rig.emulator->plant().time_s();
  double zero_at = -1.0;
  rig.Run(0.05, [&] {
    if (zero_at < 0 && MaxAbs(rig.emulator->plant().motor_current_A()) < 1e-3)
      zero_at = rig.emulator->plant().time_s();
  });
  ASSERT_GE(zero_at, 0.0);
  EXPECT_LE(zero_at - stopped_at, 0.005);
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::CommandWatchdog);
  EXPECT_EQ(rig.emulator->node().state(), fp::NodeState::Fault);

  // A new host process on the same bus: it learns of the fault and renders nothing.
  rig.arm = std::make_unique<CanArm>(rig.host_ep, CanArmConfig{});
  rig.host_running = true;
  rig.arm->Open();
  rig.arm->SetTipForce(f);
  rig.Run(0.3);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kNodeFault);
  EXPECT_EQ(rig.arm->node_fault(), fp::FaultCode::CommandWatchdog);
  EXPECT_LT(MaxAbs(rig.emulator->plant().motor_current_A()), 1e-3);
  EXPECT_FALSE(rig.emulator->node().enabled());

  ASSERT_EQ(rig.arm->ResetFault(), DeviceStatus::kOk);
  rig.Run(1.5);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::None);
  const Eigen::Vector3d felt = ToEigen(rig.emulator->plant().ForceOnHand());
  EXPECT_LT((felt - f).norm(), 0.05 * f.norm());
}

TEST(CanArmTest, ConfiguredNodeWatchdogIsWrittenBeforeEnable) {
  CanArmConfig config;
  config.node_watchdog_timeout = 20ms;
  BridgeRig rig(config);
  rig.arm->Open();
  rig.Run(0.3);
  ASSERT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  EXPECT_EQ(rig.emulator->node().parameters().u32(fp::param::kWatchdogTimeout_us), 20000u);
  rig.arm->SetTipForce(Eigen::Vector3d(0.5, 0.0, 1.0));
  rig.Run(0.3);
  rig.host_running = false;
  rig.Run(0.015);  // 15 ms silent: within the longer watchdog
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::None);
  rig.Run(0.010);
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::CommandWatchdog);
}

TEST(CanArmTest, LossIsDetectedReportedAndReconnects) {
  BridgeRig rig;
  rig.arm->Open();
  rig.Run(0.2);
  rig.arm->SetTipForce(Eigen::Vector3d(0.5, 0.5, 1.0));
  rig.Run(0.2);
  ASSERT_EQ(rig.arm->Status(), DeviceStatus::kOk);

  rig.arm_ep.set_connected(false);  // cable pulled
  rig.Run(0.005);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kOk);  // 5 ms < 10 ms loss timeout
  rig.Run(0.010);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kLinkLost);
  EXPECT_EQ(rig.arm->link_loss_count(), 1u);
  EXPECT_EQ(rig.arm->last_command().current_A, Eigen::Vector3d::Zero());  // commanding stopped
  rig.Run(0.1);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kLinkLost);

  rig.arm_ep.set_connected(true);
  rig.Run(0.05);
  EXPECT_EQ(rig.arm->link_restore_count(), 1u);
  // The node's watchdog fired while the cable was out: reported, not silently re-enabled.
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kNodeFault);
  EXPECT_EQ(rig.arm->node_fault(), fp::FaultCode::CommandWatchdog);
  rig.arm->ResetFault();
  rig.Run(0.3);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  EXPECT_GT(MaxAbs(rig.emulator->plant().motor_current_A()), 0.05);
}

// vesica-armsim restarted faster than the loss timeout (a script's `kill; vesica-armsim &`): the
// link never reads lost, but the node's boot-up heartbeat says it is a new node, so the bridge
// negotiates again and writes its watchdog setting again (the new node booted with 3 ms, which a
// host without real-time scheduling trips), and the arm returns to ok.
TEST(CanArmTest, NodeRebootWithinTheLossTimeoutRedoesTheHandshake) {
  CanArmConfig config;
  config.node_watchdog_timeout = 20ms;
  BridgeRig rig(config);
  rig.arm->Open();
  rig.Run(0.3);
  ASSERT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  for (int i = 0; i < 150; ++i) rig.Run(0.001);  // the new node's counters read as fresh, not stale
  const std::uint32_t boots = rig.arm->node_boot_count();
  rig.KillArm();
  rig.Run(0.003);
  rig.StartArm();
  EXPECT_EQ(rig.emulator->node().parameters().u32(fp::param::kWatchdogTimeout_us), 3000u);
  rig.Run(0.5);
  EXPECT_EQ(rig.arm->link_loss_count(), 0u);
  EXPECT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  EXPECT_EQ(rig.arm->node_boot_count(), boots + 1);
  EXPECT_EQ(rig.emulator->node().parameters().u32(fp::param::kWatchdogTimeout_us), 20000u);
  EXPECT_TRUE(rig.emulator->node().enabled());
}

// Two arms (node ids 1 and 2) and two bridges on one classic 1 Mbit/s bus at 1 kHz: both render
// their own force, and the measured bus load stays within the 60% budget.
TEST(CanArmTest, TwoArmsShareOneBusWithinLoadBudget) {
  BridgeRig rig;  // arm 1 on "arm", host 1 on "host"
  fp::VirtualBusEndpoint& arm2_ep = rig.bus.attach("arm2");
  fp::VirtualBusEndpoint& host2_ep = rig.bus.attach("host2");
  fp::emulator::ArmEmulator::Config ec;
  ec.node_id = 2;
  const fp::emulator::Joint4 q2{-0.3, 0.2, 0.0, 0.1};
  ec.board.park_position = {-0.3f, 0.2f, 0.1f};
  fp::emulator::ArmEmulator arm2(arm2_ep, fp::emulator::ArmPlantParameters::Nominal(), q2, ec);
  fp::emulator::HandTarget hold2;
  hold2.p_T = fp::emulator::TipPosition(q2);
  arm2.plant().SetHandScript(fp::emulator::HandScript(hold2));
  CanArmConfig c2;
  c2.node_id = 2;
  CanArm host2(host2_ep, c2);
  ASSERT_EQ(arm2.node().node_id(), 2);

  rig.arm->Open();
  host2.Open();
  const Eigen::Vector3d f1(1.0, 0.0, 1.0), f2(-0.5, 0.8, 0.6);
  rig.arm->SetTipForce(f1);
  host2.SetTipForce(f2);
  auto run = [&](double s) {
    rig.Run(s, [&] {
      arm2.RunUntil(rig.clock.now());
      host2.Tick();
    });
  };
  run(0.5);
  rig.bus.reset_load();
  run(1.5);
  const double load = rig.bus.load();
  RecordProperty("bus_load_two_arms", std::to_string(load));
  ASSERT_EQ(rig.arm->Status(), DeviceStatus::kOk);
  ASSERT_EQ(host2.Status(), DeviceStatus::kOk);
  EXPECT_LT((ToEigen(rig.emulator->plant().ForceOnHand()) - f1).norm(), 0.05 * f1.norm());
  EXPECT_LT((ToEigen(arm2.plant().ForceOnHand()) - f2).norm(), 0.05 * f2.norm());
  EXPECT_LT(load, 0.60);
  EXPECT_GT(load, 0.40);  // 4 frames of ~120 bits per ms plus 100 Hz traffic: about half the bus
  EXPECT_EQ(rig.arm->decode_errors().total(), 0u);
  EXPECT_EQ(host2.decode_errors().total(), 0u);
}

TEST(CanArmTest, RoundTripAndPeriodStatisticsOnVirtualBus) {
  BridgeRig rig;
  rig.arm->Open();
  rig.Run(1.0);
  const auto period = rig.arm->loop_period();
  EXPECT_EQ(period.p50_ns, 1e6);  // ticks exactly every 1 ms of bus time
  EXPECT_EQ(period.p99_ns, 1e6);
  const auto rt = rig.arm->round_trip();
  EXPECT_GT(rt.count, 900u);
  // Command frame (~0.13 ms at 1 Mbit/s) + node tick (<= 0.1 ms) + state frame: under 0.5 ms.
  EXPECT_GT(rt.p50_ns, 1e5);
  EXPECT_LT(rt.p99_ns, 5e5);
}

}  // namespace
}  // namespace vesica::device
