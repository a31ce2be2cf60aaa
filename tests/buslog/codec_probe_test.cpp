// The codec probe finds the rules a field's range alone does not say: NMT's five commands, the
// unused bits the codec requires to be zero; and it has a valid frame of every message to start from.
#include "firmware_protocol/wireshark/codec_probe.h"

#include <gtest/gtest.h>

namespace vesica::fp {
namespace {

TEST(CodecProbeTest, NmtCommandAcceptsOnlyTheFiveCiA301Commands) {
  const CodecProbe p = probe_codec(MessageKind::Nmt);
  ASSERT_TRUE(p.probed);
  ASSERT_EQ(p.enumerations.size(), 1u);
  EXPECT_EQ(p.enumerations[0].field, &fields::Nmt::command);
  EXPECT_EQ(p.enumerations[0].valid_raw, (std::vector<std::int64_t>{0x01, 0x02, 0x80, 0x81, 0x82}));
  EXPECT_TRUE(p.reserved.empty());
}

TEST(CodecProbeTest, UnusedInputAndStateBitsMustBeZero) {
  const CodecProbe aux = probe_codec(MessageKind::AuxState);
  ASSERT_EQ(aux.reserved.size(), 1u);
  EXPECT_EQ(aux.reserved[0].offset, 1);
  EXPECT_EQ(aux.reserved[0].mask, 0xF8);  // pedal, estop_input, handle_button use bits 0..2
  const CodecProbe hb = probe_codec(MessageKind::Heartbeat);
  ASSERT_EQ(hb.reserved.size(), 1u);
  EXPECT_EQ(hb.reserved[0].offset, 1);
  EXPECT_EQ(hb.reserved[0].mask, 0xE0);  // state bits 0..2, enabled bit 3, not_homed bit 4 (1.4)
  EXPECT_TRUE(probe_codec(MessageKind::JointState).reserved.empty());  // byte 1 fully used
}

TEST(CodecProbeTest, EveryMessageHasAValidFrameToProbeFrom) {
  for (const MessageSpec& s : kMessageSpecs) EXPECT_TRUE(probe_codec(s.kind).probed) << s.name;
}

}  // namespace
}  // namespace vesica::fp
