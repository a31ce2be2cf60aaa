// The committed dissector (tools/wireshark/vesica.lua) is exactly what the generator makes from
// today's message table and codec; the codec probe finds the rules the range alone does not say.
#include "firmware_protocol/wireshark/wireshark_dissector.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "firmware_protocol/wireshark/codec_probe.h"
#include "firmware_protocol/wireshark/field_bits.h"
#include "firmware_protocol/wireshark/value_names.h"

namespace vesica::fp {
namespace {

TEST(WiresharkDissectorTest, CommittedFileEqualsAFreshGeneration) {
  const std::string path = std::string(VESICA_SOURCE_DIR) + "/tools/wireshark/vesica.lua";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_TRUE(committed.str() == wireshark_dissector_lua())
      << path << " is stale: cmake --build build/release --target wireshark_dissector && cp build/release/wireshark/vesica.lua "
      << path;
}

TEST(WiresharkDissectorTest, EveryMessageAndFieldOfTheTableIsInTheDissector) {
  const std::string lua = wireshark_dissector_lua();
  for (const MessageSpec& s : kMessageSpecs)
    EXPECT_NE(lua.find("{name = \"" + std::string(s.name) + "\""), std::string::npos) << s.name;
  for (const FieldSpec* f : kAllFields) {
    const std::string abbrev = std::string("\"vesica.") + spec_of(f->message).name + "." + f->name + "\"";
    EXPECT_NE(lua.find(abbrev), std::string::npos) << abbrev;
  }
}

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
  EXPECT_EQ(hb.reserved[0].mask, 0xF0);  // state bits 0..2, enabled bit 3
  EXPECT_TRUE(probe_codec(MessageKind::JointState).reserved.empty());  // byte 1 fully used
}

TEST(ValueNamesTest, EveryValueTheCodecAcceptsInANamedFieldHasAName) {
  for (const FieldValueNames& v : field_value_names()) {
    const CodecProbe probe = probe_codec(v.field->message);
    std::vector<std::int64_t> accepted;
    for (std::int64_t raw = raw_min(*v.field); raw <= raw_max(*v.field); ++raw) accepted.push_back(raw);
    for (const FieldEnumeration& e : probe.enumerations)
      if (e.field == v.field) accepted = e.valid_raw;
    std::vector<std::int64_t> named;
    for (const auto& [raw, text] : v.names) named.push_back(raw);
    EXPECT_EQ(named, accepted) << spec_of(v.field->message).name << "." << v.field->name;
  }
  bool state_named = false;
  for (const FieldValueNames& v : field_value_names()) {
    if (v.field != &fields::JointState::state) continue;
    ASSERT_EQ(v.names.size(), 5u);
    EXPECT_EQ(v.names[2], (std::pair<std::int64_t, std::string>{2, "operational"}));  // the codec's to_string
    state_named = true;
  }
  EXPECT_TRUE(state_named);
}

TEST(CodecProbeTest, EveryMessageHasAValidFrameToProbeFrom) {
  for (const MessageSpec& s : kMessageSpecs) EXPECT_TRUE(probe_codec(s.kind).probed) << s.name;
}

}  // namespace
}  // namespace vesica::fp
