// The committed dissector (tools/wireshark/vesica.lua) is exactly what the generator makes from
// today's message table and codec, and it has every message and field of the table.
#include "firmware_protocol/wireshark/wireshark_dissector.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "firmware_protocol/codec/message_table.h"

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

}  // namespace
}  // namespace vesica::fp
