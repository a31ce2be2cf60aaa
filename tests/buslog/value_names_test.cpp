// Enumerated fields have a name for every value the codec accepts (the codec's own to_string for
// node states, limiters and faults).
#include "firmware_protocol/wireshark/value_names.h"

#include "firmware_protocol/wireshark/codec_probe.h"
#include "firmware_protocol/wireshark/field_bits.h"

#include <gtest/gtest.h>

namespace vesica::fp {
namespace {

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

}  // namespace
}  // namespace vesica::fp
