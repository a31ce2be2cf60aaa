// The arm supervisor on the virtual bus (deterministic, bus clock only): watchdog faults clear
// themselves once commands flow again, other faults wait for the user, an arm process restarted
// after a fault comes back as "ok", and every state reads as one line with the fault's name.
#include "device/arm_supervisor.h"

#include <gtest/gtest.h>

#include "bridge_rig.h"
#include "firmware_protocol/codec/codec.h"

namespace vesica::device {
namespace {

using testing::BridgeRig;
using testing::ToEigen;
using namespace std::chrono_literals;

struct SupervisedRig : BridgeRig {
  std::unique_ptr<ArmSupervisor> supervisor;
  fp::VirtualBusEndpoint& pendant = bus.attach("pendant");  // another station's E-stop button

  explicit SupervisedRig(const CanArmConfig& config = {}) : BridgeRig(config) {
    ArmSupervisorConfig sc;
    sc.name = "left arm";
    sc.link = "node 1 on the test bus";
    supervisor = std::make_unique<ArmSupervisor>(*arm, sc);
    arm->Open();
  }
  void Run(double seconds) {
    BridgeRig::Run(seconds, [this] {
      if (host_running) supervisor->Tick(clock.now());
    });
  }
  std::string Text() const { return supervisor->Report().text; }
  void PressEStop() {
    fp::CanFrame f;
    ASSERT_EQ(fp::encode(fp::EStop{9}, f), fp::EncodeError::None);
    ASSERT_EQ(pendant.send(f, clock.now() + 1ms), fp::SendStatus::Queued);
  }
};

TEST(ArmSupervisorTest, ReportsOkAsOneLine) {
  SupervisedRig rig;
  rig.Run(0.3);
  const ArmReport r = rig.supervisor->Report();
  EXPECT_EQ(r.status, DeviceStatus::kOk);
  EXPECT_EQ(r.fault, fp::FaultCode::None);
  EXPECT_EQ(r.text, "left arm: ok");
}

// The host stalled longer than the node's watchdog (3 ms) but not the loss timeout (10 ms): the
// node latched command_watchdog. Its cause (the host's silence) is gone once states flow again,
// so the supervisor clears it and force returns, without the user and without reopening.
TEST(ArmSupervisorTest, WatchdogFaultClearsItselfOnceCommandsFlowAgain) {
  SupervisedRig rig;
  rig.Run(0.3);
  const Eigen::Vector3d f(1.0, -0.5, 1.5);
  rig.arm->SetTipForce(f);
  rig.Run(0.3);
  ASSERT_EQ(rig.Text(), "left arm: ok");

  rig.host_running = false;
  rig.Run(0.006);
  rig.host_running = true;
  rig.Run(0.05);
  EXPECT_EQ(rig.Text(), "left arm: FAULT command_watchdog");
  EXPECT_EQ(rig.supervisor->Report().fault, fp::FaultCode::CommandWatchdog);

  rig.Run(1.0);
  const ArmReport r = rig.supervisor->Report();
  EXPECT_EQ(r.text, "left arm: ok");
  EXPECT_EQ(r.automatic_fault_resets, 1u);
  EXPECT_EQ(r.requested_fault_resets, 0u);
  const Eigen::Vector3d felt = ToEigen(rig.emulator->plant().ForceOnHand());
  EXPECT_LT((felt - f).norm(), 0.05 * f.norm()) << felt.transpose();
}

// Cable out for 100 ms: "link lost" while it is out; when it is back the watchdog fault the
// node latched meanwhile is cleared and the arm is ok again.
TEST(ArmSupervisorTest, LinkLossIsNamedAndTheArmRecoversWhenTheLinkReturns) {
  SupervisedRig rig;
  rig.Run(0.3);
  rig.arm_ep.set_connected(false);
  rig.Run(0.1);
  EXPECT_EQ(rig.Text(), "left arm: link lost");
  EXPECT_EQ(rig.supervisor->Report().link_losses, 1u);
  rig.arm_ep.set_connected(true);
  rig.Run(1.0);
  EXPECT_EQ(rig.Text(), "left arm: ok");
  EXPECT_EQ(rig.supervisor->Report().automatic_fault_resets, 1u);
}

// An E-stop is a person's decision: the fault is shown by name and stays until the user clears
// it; then the arm is ok without reopening anything.
TEST(ArmSupervisorTest, EStopFaultWaitsForTheUserThenClears) {
  SupervisedRig rig;
  rig.Run(0.3);
  rig.PressEStop();
  rig.Run(2.0);
  EXPECT_EQ(rig.Text(), "left arm: FAULT emergency_stop");
  EXPECT_EQ(rig.supervisor->Report().automatic_fault_resets, 0u);
  rig.supervisor->RequestFaultReset();
  rig.Run(0.5);
  const ArmReport r = rig.supervisor->Report();
  EXPECT_EQ(r.text, "left arm: ok");
  EXPECT_EQ(r.requested_fault_resets, 1u);
}

// The user restarts vesica-armsim after a fault: the new process's node has no fault, so the
// arm is ok again once it has answered; the old node's fault is not carried over.
TEST(ArmSupervisorTest, ArmRestartedAfterAFaultReturnsToOk) {
  SupervisedRig rig;
  rig.Run(0.3);
  rig.PressEStop();
  rig.Run(0.5);
  ASSERT_EQ(rig.Text(), "left arm: FAULT emergency_stop");
  rig.KillArm();
  rig.Run(0.5);
  EXPECT_EQ(rig.Text(), "left arm: link lost");
  rig.StartArm();
  rig.Run(1.0);
  EXPECT_EQ(rig.Text(), "left arm: ok");
  EXPECT_EQ(rig.arm->node_fault(), fp::FaultCode::None);
  EXPECT_EQ(rig.supervisor->Report().requested_fault_resets, 0u);
}

// Nothing answers (no vesica-armsim running): after no_answer_after the line says where the
// bridge is looking; before that it says it is waiting.
TEST(ArmSupervisorTest, SilentNodeIsNamedWithWhereTheBridgeLooks) {
  SupervisedRig rig;
  rig.KillArm();
  rig.Run(1.0);
  EXPECT_EQ(rig.Text(), "left arm: waiting for node 1 on the test bus");
  rig.Run(1.5);
  EXPECT_EQ(rig.Text(), "left arm: no answer from node 1 on the test bus");
  EXPECT_EQ(rig.supervisor->Report().status, DeviceStatus::kConnecting);
}

}  // namespace
}  // namespace vesica::device
