// UdpStylus against an in-process fake device (a UdpDatagramSocket on loopback), with the host
// clock injected: the loss threshold and the force rules are checked exactly, not against a
// wall clock.
#include "device/stylus/udp_stylus.h"

#include <gtest/gtest.h>

#include <limits>
#include <thread>

namespace vesica::device {
namespace {

constexpr std::int64_t kMs = 1'000'000;

class UdpStylusTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_NO_FATAL_FAILURE(Connect(0.0)); }

  // A stylus on a free port and the fake device on another, each pointed at the other.
  void Connect(double force_ramp_s) {
    std::string error;
    device_.reset();
    auto probe = UdpDatagramSocket::Open({"127.0.0.1", 0}, {"127.0.0.1", 9}, &error);
    ASSERT_TRUE(probe) << error;
    const std::uint16_t device_port = probe->local_port();
    probe.reset();
    UdpStylusConfig config;
    config.local.port = 0;
    config.device.port = device_port;
    config.force_ramp_s = force_ramp_s;
    stylus_ = std::make_unique<UdpStylus>(config);
    ASSERT_EQ(stylus_->Open(), DeviceStatus::kConnecting);
    device_ = UdpDatagramSocket::Open({"127.0.0.1", device_port}, {"127.0.0.1", stylus_->local_port()}, &error);
    ASSERT_TRUE(device_) << error;
  }

  void SendPose(std::uint32_t sequence, Eigen::Vector3d p = {0.01, 0.02, 0.03}) {
    OmniPoseDatagram pose;
    pose.sequence = sequence;
    pose.p_BTip_B = p;
    pose.d_B = {0.0, 0.0, -2.0};  // not unit on the wire: the stylus makes it unit
    pose.buttons = kStylusButton1;
    SendBytes(EncodeOmniPose(pose));
  }
  void SendBytes(std::span<const std::uint8_t> bytes) {
    std::string error;
    ASSERT_TRUE(device_->Send(bytes, &error)) << error;
    // Loopback delivers inside sendto in practice; the pause only guards a descheduled softirq.
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  // The last force datagram the stylus sent, if any.
  std::optional<OmniForceDatagram> LastForce() {
    std::array<std::uint8_t, 512> buf{};
    bool from_peer = false;
    std::optional<OmniForceDatagram> last;
    for (long n; (n = device_->Receive(buf, &from_peer)) >= 0;) {
      OmniForceDatagram f;
      if (!DecodeOmniForce(std::span<const std::uint8_t>(buf.data(), static_cast<std::size_t>(n)), &f)) last = f;
    }
    return last;
  }

  std::unique_ptr<UdpDatagramSocket> device_;
  std::unique_ptr<UdpStylus> stylus_;
};

TEST_F(UdpStylusTest, FirstPoseBringsTheLinkUp) {
  stylus_->Tick(1000 * kMs);
  EXPECT_EQ(stylus_->Status(), DeviceStatus::kConnecting);
  EXPECT_NE(stylus_->StatusText().find("waiting for the first pose"), std::string::npos);
  SendPose(1);
  stylus_->Tick(1001 * kMs);
  EXPECT_EQ(stylus_->Status(), DeviceStatus::kOk);
  const StylusState s = stylus_->GetStylusState();
  EXPECT_EQ(s.p_BTip_B, Eigen::Vector3d(0.01, 0.02, 0.03));
  EXPECT_EQ(s.d_B, Eigen::Vector3d(0.0, 0.0, -1.0));
  EXPECT_EQ(s.buttons, kStylusButton1);
  EXPECT_EQ(stylus_->last_pose_arrival_ns(), 1001 * kMs);
}

// Lost exactly when more than loss_timeout (9 ms) has passed since the last pose: at 9 ms it is
// still up, 1 ns later it is lost; with 1 kHz ticks that is reported within 10 ms.
TEST_F(UdpStylusTest, LossIsReportedAtTheFirstTickPastNineMilliseconds) {
  SendPose(1);
  stylus_->Tick(1000 * kMs);
  ASSERT_EQ(stylus_->SetTipForce({1.0, 0.0, 0.0}), DeviceStatus::kOk);
  stylus_->Tick(1009 * kMs);
  EXPECT_EQ(stylus_->Status(), DeviceStatus::kOk);
  EXPECT_EQ(stylus_->RenderedForce(), Eigen::Vector3d(1.0, 0.0, 0.0));
  stylus_->Tick(1009 * kMs + 1);
  EXPECT_EQ(stylus_->Status(), DeviceStatus::kLinkLost);
  EXPECT_EQ(stylus_->link_lost_at_ns(), 1009 * kMs + 1);
  EXPECT_EQ(stylus_->RenderedForce(), Eigen::Vector3d::Zero());
  const auto sent = LastForce();
  ASSERT_TRUE(sent);
  EXPECT_EQ(sent->f_B, Eigen::Vector3d::Zero());
  const std::string text = stylus_->StatusText();
  EXPECT_NE(text.find("no pose datagram for 9.0 ms"), std::string::npos) << text;
  EXPECT_NE(text.find("link lost, force off"), std::string::npos) << text;
  // While lost a force request is refused, not kept for later.
  EXPECT_EQ(stylus_->SetTipForce({0.5, 0.0, 0.0}), DeviceStatus::kLinkLost);
  EXPECT_EQ(stylus_->link_loss_count(), 1u);
}

TEST_F(UdpStylusTest, RecoveryRestartsForceFromZeroAndAcceptsARestartedSequence) {
  SendPose(500);
  stylus_->Tick(1000 * kMs);
  ASSERT_EQ(stylus_->SetTipForce({0.0, 2.0, 0.0}), DeviceStatus::kOk);
  stylus_->Tick(1020 * kMs);
  ASSERT_EQ(stylus_->Status(), DeviceStatus::kLinkLost);
  SendPose(1);  // the emulator restarted: its sequence starts again
  stylus_->Tick(1030 * kMs);
  EXPECT_EQ(stylus_->Status(), DeviceStatus::kOk);
  EXPECT_EQ(stylus_->link_restore_count(), 1u);
  EXPECT_EQ(stylus_->last_pose_sequence(), 1u);
  EXPECT_EQ(stylus_->RenderedForce(), Eigen::Vector3d::Zero());  // not the 2 N from before the loss
  const auto sent = LastForce();
  ASSERT_TRUE(sent);
  EXPECT_EQ(sent->f_B, Eigen::Vector3d::Zero());
  EXPECT_EQ(sent->pose_sequence, 1u);
}

TEST(UdpStylusForeignTest, DatagramsFromAnotherPortAreDropped) {
  UdpStylusConfig config;
  config.local.port = 0;
  config.device.port = 9;
  config.force_ramp_s = 0.05;
  UdpStylus stylus(config);
  ASSERT_EQ(stylus.Open(), DeviceStatus::kConnecting);
  std::string error;
  auto device = UdpDatagramSocket::Open({"127.0.0.1", 0}, {"127.0.0.1", stylus.local_port()}, &error);
  ASSERT_TRUE(device);
  // The stylus only takes poses from its configured device port; this one is foreign.
  OmniPoseDatagram pose;
  pose.sequence = 1;
  const auto bytes = EncodeOmniPose(pose);
  ASSERT_TRUE(device->Send(bytes, &error));
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  stylus.Tick(0);
  EXPECT_EQ(stylus.Status(), DeviceStatus::kConnecting);
  EXPECT_EQ(stylus.datagrams_rejected(), 1u);
  EXPECT_NE(stylus.last_rejection().find("another address"), std::string::npos);
}

TEST_F(UdpStylusTest, RampHalfwayGivesHalfTheForce) {
  ASSERT_NO_FATAL_FAILURE(Connect(0.05));
  SendPose(1);
  stylus_->Tick(100 * kMs);
  ASSERT_EQ(stylus_->SetTipForce({0.0, 0.0, 2.0}), DeviceStatus::kOk);
  SendPose(2);
  stylus_->Tick(125 * kMs);
  EXPECT_NEAR(stylus_->RenderedForce().z(), 1.0, 1e-12);
  SendPose(3);
  stylus_->Tick(150 * kMs);
  EXPECT_NEAR(stylus_->RenderedForce().z(), 2.0, 1e-12);
}

TEST_F(UdpStylusTest, BadDatagramsLeaveTheStateUnchanged) {
  SendPose(10, {0.01, 0.0, 0.0});
  stylus_->Tick(1000 * kMs);
  ASSERT_EQ(stylus_->Status(), DeviceStatus::kOk);
  const StylusState before = stylus_->GetStylusState();

  OmniPoseDatagram nan_pose;
  nan_pose.sequence = 11;
  nan_pose.p_BTip_B = {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
  SendBytes(EncodeOmniPose(nan_pose));
  stylus_->Tick(1001 * kMs);
  EXPECT_NE(stylus_->last_rejection().find("stylus position"), std::string::npos) << stylus_->last_rejection();

  OmniPoseDatagram zero_direction;
  zero_direction.sequence = 12;
  zero_direction.d_B.setZero();
  SendBytes(EncodeOmniPose(zero_direction));
  stylus_->Tick(1002 * kMs);
  EXPECT_NE(stylus_->last_rejection().find("zero length"), std::string::npos) << stylus_->last_rejection();

  const std::uint8_t garbage[] = {'G', 'E', 'T', ' ', '/'};
  SendBytes(garbage);
  stylus_->Tick(1003 * kMs);
  EXPECT_NE(stylus_->last_rejection().find("without the magic"), std::string::npos) << stylus_->last_rejection();

  SendPose(9, {0.05, 0.0, 0.0});  // older than the last good one
  stylus_->Tick(1004 * kMs);
  EXPECT_NE(stylus_->last_rejection().find("duplicate or reordered"), std::string::npos);

  EXPECT_EQ(stylus_->datagrams_rejected(), 4u);
  const StylusState after = stylus_->GetStylusState();
  EXPECT_EQ(after.p_BTip_B, before.p_BTip_B);
  EXPECT_EQ(after.d_B, before.d_B);
  EXPECT_EQ(stylus_->last_pose_sequence(), 10u);
  // Garbage is not a sign of life: the link is lost 9 ms after the last good pose all the same.
  stylus_->Tick(1009 * kMs + 1);
  EXPECT_EQ(stylus_->Status(), DeviceStatus::kLinkLost);
}

TEST_F(UdpStylusTest, NonFiniteForceIsRefusedAndTheForceInUseKept) {
  SendPose(1);
  stylus_->Tick(1000 * kMs);
  ASSERT_EQ(stylus_->SetTipForce({0.0, 1.0, 0.0}), DeviceStatus::kOk);
  EXPECT_EQ(stylus_->SetTipForce({0.0, std::numeric_limits<double>::quiet_NaN(), 0.0}), DeviceStatus::kInvalidArgument);
  EXPECT_EQ(stylus_->RenderedForce(), Eigen::Vector3d(0.0, 1.0, 0.0));
  // Saturated to 3.3 N with the direction kept.
  ASSERT_EQ(stylus_->SetTipForce({0.0, 0.0, -10.0}), DeviceStatus::kOk);
  EXPECT_EQ(stylus_->RenderedForce(), Eigen::Vector3d(0.0, 0.0, -3.3));
}

TEST(UdpStylusOpenTest, BadConfigurationIsRefused) {
  UdpStylusConfig config;
  config.loss_timeout_ns = 0;
  EXPECT_THROW(UdpStylus{config}, std::invalid_argument);
  config = {};
  config.force_ramp_s = -0.01;
  EXPECT_THROW(UdpStylus{config}, std::invalid_argument);
}

TEST(UdpStylusOpenTest, APortInUseIsATransportErrorNamingThePort) {
  std::string error;
  auto holder = UdpDatagramSocket::Open({"127.0.0.1", 0}, {"127.0.0.1", 9}, &error);
  ASSERT_TRUE(holder);
  UdpStylusConfig config;
  config.local.port = holder->local_port();
  UdpStylus stylus(config);
  EXPECT_EQ(stylus.Open(), DeviceStatus::kTransportError);
  EXPECT_EQ(stylus.Status(), DeviceStatus::kTransportError);
  EXPECT_NE(stylus.StatusText().find("cannot bind UDP 127.0.0.1:" + std::to_string(holder->local_port())),
            std::string::npos)
      << stylus.StatusText();
}

}  // namespace
}  // namespace vesica::device
