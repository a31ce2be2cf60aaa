// docs/protocol.md's tables are exactly what the message/parameter/fault tables generate (one
// source of truth). On failure, run can_print_protocol_tables and paste the block named.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "firmware_protocol/docgen/protocol_tables.h"

namespace vesica::fp {
namespace {

std::string read_doc() {
  std::ifstream in(std::string(VESICA_SOURCE_DIR) + "/docs/protocol.md");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ProtocolDocTest, GeneratedTablesMatchTheCode) {
  const std::string doc = read_doc();
  ASSERT_FALSE(doc.empty()) << "docs/protocol.md missing";
  for (const std::string& name : protocol_table_names()) {
    const std::string begin = "<!-- BEGIN GENERATED: " + name + " -->\n";
    const std::string end = "<!-- END GENERATED: " + name + " -->";
    const auto b = doc.find(begin);
    const auto e = doc.find(end);
    ASSERT_NE(b, std::string::npos) << "docs/protocol.md lacks the block " << name;
    ASSERT_NE(e, std::string::npos) << "docs/protocol.md lacks the end of block " << name;
    const std::string in_doc = doc.substr(b + begin.size(), e - b - begin.size());
    EXPECT_EQ(in_doc, protocol_table(name)) << "table '" << name << "' in docs/protocol.md is stale";
  }
}

TEST(ProtocolDocTest, BandwidthTableStatesTheBudgetTheTestAsserts) {
  const std::string t = protocol_table("bandwidth");
  EXPECT_NE(t.find("**59.57 %**"), std::string::npos) << t;
}

}  // namespace
}  // namespace vesica::fp
