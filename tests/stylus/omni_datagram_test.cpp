#include "device/stylus/omni_datagram.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "device/stylus/stylus_state.h"

namespace vesica::device {
namespace {

OmniPoseDatagram SomePose() {
  OmniPoseDatagram p;
  p.sequence = 0xfffffffe;
  p.buttons = kStylusButton1;
  p.timestamp_ns = -123456789012345;
  p.p_BTip_B = {0.0125, -0.03, 1.0 / 3.0};
  p.d_B = Eigen::Vector3d(0.1, -0.9, -0.4).normalized();
  return p;
}

TEST(OmniDatagramTest, PoseRoundTripIsExact) {
  const OmniPoseDatagram in = SomePose();
  const OmniPoseBytes bytes = EncodeOmniPose(in);
  OmniPoseDatagram out;
  ASSERT_EQ(DecodeOmniPose(bytes, &out), std::nullopt);
  EXPECT_EQ(out.sequence, in.sequence);
  EXPECT_EQ(out.buttons, in.buttons);
  EXPECT_EQ(out.timestamp_ns, in.timestamp_ns);
  EXPECT_EQ(out.p_BTip_B, in.p_BTip_B);
  EXPECT_EQ(out.d_B, in.d_B);
}

TEST(OmniDatagramTest, ForceRoundTripIsExact) {
  OmniForceDatagram in;
  in.sequence = 7;
  in.pose_sequence = 4711;
  in.timestamp_ns = 99;
  in.f_B = {-1.5, 0.25, 3.25};
  OmniForceDatagram out;
  ASSERT_EQ(DecodeOmniForce(EncodeOmniForce(in), &out), std::nullopt);
  EXPECT_EQ(out.sequence, 7u);
  EXPECT_EQ(out.pose_sequence, 4711u);
  EXPECT_EQ(out.timestamp_ns, 99);
  EXPECT_EQ(out.f_B, in.f_B);
}

// The layout is little-endian at fixed offsets (docs/omni.md's table): checked byte by byte.
TEST(OmniDatagramTest, LayoutIsLittleEndianAtDocumentedOffsets) {
  OmniPoseDatagram p;
  p.sequence = 0x04030201;
  p.buttons = 0x2;
  p.timestamp_ns = 0x0807060504030201;
  p.p_BTip_B = {1.0, 0.0, 0.0};
  const OmniPoseBytes b = EncodeOmniPose(p);
  EXPECT_EQ(std::vector<std::uint8_t>(b.begin(), b.begin() + 8),
            (std::vector<std::uint8_t>{'V', 'O', 'M', 'N', 1, 1, 0, 0}));
  EXPECT_EQ(b[8], 0x01);
  EXPECT_EQ(b[11], 0x04);
  EXPECT_EQ(b[12], 0x02);
  EXPECT_EQ(b[16], 0x01);
  EXPECT_EQ(b[23], 0x08);
  // 1.0 = 0x3ff0000000000000
  EXPECT_EQ(b[30], 0xf0);
  EXPECT_EQ(b[31], 0x3f);
  EXPECT_EQ(EncodeOmniForce({}).size(), 48u);
  EXPECT_EQ(EncodeOmniForce({})[5], 2);
}

std::string PoseError(std::vector<std::uint8_t> bytes) {
  OmniPoseDatagram out = SomePose();
  const OmniPoseDatagram before = out;
  const auto problem = DecodeOmniPose(bytes, &out);
  // A refused datagram leaves the output untouched.
  EXPECT_EQ(out.sequence, before.sequence);
  EXPECT_EQ(out.p_BTip_B, before.p_BTip_B);
  return problem.value_or("");
}

std::vector<std::uint8_t> PoseBytes(const OmniPoseDatagram& p) {
  const OmniPoseBytes b = EncodeOmniPose(p);
  return {b.begin(), b.end()};
}

TEST(OmniDatagramTest, GarbageGetsAClearReason) {
  EXPECT_NE(PoseError({}).find("without the magic"), std::string::npos);
  EXPECT_NE(PoseError({'h', 'e', 'l', 'l', 'o'}).find("without the magic 'VOMN'"), std::string::npos);
  EXPECT_NE(PoseError({'V', 'O', 'M', 'N', 1}).find("too short for a header"), std::string::npos);

  auto b = PoseBytes(SomePose());
  b[4] = 2;
  EXPECT_NE(PoseError(b).find("protocol version 2, this build speaks version 1"), std::string::npos) << PoseError(b);

  b = PoseBytes(SomePose());
  b[5] = 2;
  EXPECT_NE(PoseError(b).find("kind 2 (force) where a pose datagram was expected"), std::string::npos) << PoseError(b);

  b = PoseBytes(SomePose());
  b.pop_back();
  EXPECT_NE(PoseError(b).find("71 bytes, a version 1 pose datagram is exactly 72"), std::string::npos) << PoseError(b);

  b = PoseBytes(SomePose());
  b[7] = 0x80;
  EXPECT_NE(PoseError(b).find("reserved field"), std::string::npos) << PoseError(b);
}

TEST(OmniDatagramTest, NaNPoseAndZeroDirectionAreRefused) {
  OmniPoseDatagram p = SomePose();
  p.p_BTip_B.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(PoseError(PoseBytes(p)).find("stylus position"), std::string::npos) << PoseError(PoseBytes(p));
  p = SomePose();
  p.d_B.setZero();
  EXPECT_NE(PoseError(PoseBytes(p)).find("zero length"), std::string::npos) << PoseError(PoseBytes(p));
  EXPECT_NE(PoseError(PoseBytes(p)).find("sequence 4294967294"), std::string::npos) << PoseError(PoseBytes(p));
  p = SomePose();
  p.buttons = 0x10;
  EXPECT_NE(PoseError(PoseBytes(p)).find("buttons"), std::string::npos);

  OmniForceDatagram f;
  f.f_B.z() = std::numeric_limits<double>::infinity();
  OmniForceDatagram out;
  const auto problem = DecodeOmniForce(EncodeOmniForce(f), &out);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("force is not finite"), std::string::npos);
  EXPECT_EQ(out.f_B, Eigen::Vector3d::Zero());
}

// Any byte sequence decodes to a datagram or a reason, never a crash (run under ASan in the
// sanitizer build).
TEST(OmniDatagramTest, RandomBytesNeverCrash) {
  std::mt19937 rng(34);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 100);
  int refused = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<std::uint8_t> b(static_cast<std::size_t>(length(rng)));
    for (auto& x : b) x = static_cast<std::uint8_t>(byte(rng));
    // Half of them with a valid header, so the decoder gets past the magic.
    if (i % 2 == 0 && b.size() >= 8) {
      const auto good = PoseBytes(SomePose());
      std::copy(good.begin(), good.begin() + 8, b.begin());
    }
    OmniPoseDatagram pose;
    OmniForceDatagram force;
    refused += DecodeOmniPose(b, &pose).has_value();
    refused += DecodeOmniForce(b, &force).has_value();
  }
  EXPECT_GT(refused, 39000);
}

}  // namespace
}  // namespace vesica::device
