// The message table is self-consistent: ids do not collide, fields fit their frames and do not overlap.
#include "firmware_protocol/codec/codec.h"

#include <gtest/gtest.h>

namespace vesica::fp {
namespace {

TEST(MessageTableTest, SpecsAreInVariantOrder) {
  for (std::size_t k = 0; k < kMessageKindCount; ++k)
    EXPECT_EQ(static_cast<std::size_t>(kMessageSpecs[k].kind), k) << kMessageSpecs[k].name;
  EXPECT_EQ(std::variant_size_v<Message>, kMessageKindCount);
}

TEST(MessageTableTest, NoTwoMessagesShareAnIdentifier) {
  // Every id 0..0x7FF maps to at most one message; classify_id agrees with can_id.
  for (std::size_t k = 0; k < kMessageKindCount; ++k) {
    const MessageSpec& s = kMessageSpecs[k];
    for (std::uint8_t node = s.per_node ? 1 : 0; node <= (s.per_node ? kMaxNodeId : 0); ++node) {
      MessageKind kind;
      std::uint8_t n;
      const std::uint16_t id = can_id(s.kind, node);
      ASSERT_TRUE(classify_id(id, kind, n)) << s.name;
      EXPECT_EQ(kind, s.kind) << s.name << " node " << int(node) << " id " << id;
      EXPECT_EQ(n, node);
    }
  }
}

TEST(MessageTableTest, CanopenIdsKeepTheirPlaces) {
  EXPECT_EQ(can_id(MessageKind::Nmt, 0), 0x000);
  EXPECT_EQ(can_id(MessageKind::Sync, 0), 0x080);
  EXPECT_EQ(can_id(MessageKind::Emergency, 5), 0x085);
  EXPECT_EQ(can_id(MessageKind::ParameterResponse, 5), 0x585);
  EXPECT_EQ(can_id(MessageKind::ParameterRequest, 5), 0x605);
  EXPECT_EQ(can_id(MessageKind::Heartbeat, 5), 0x705);
}

TEST(MessageTableTest, FieldsFitTheirFrameAndDoNotOverlap) {
  for (const MessageSpec& s : kMessageSpecs) {
    std::uint8_t bits_used[8] = {};
    for (const FieldSpec* f : kAllFields) {
      if (f->message != s.kind) continue;
      ASSERT_LE(f->offset + wire_size(f->type), s.length) << s.name << "." << f->name;
      for (int b = 0; b < wire_size(f->type); ++b) {
        std::uint8_t mask = 0xFF;
        if (f->bit_width) mask = static_cast<std::uint8_t>(((1u << f->bit_width) - 1u) << f->bit_offset);
        EXPECT_EQ(bits_used[f->offset + b] & mask, 0) << s.name << "." << f->name << " overlaps";
        bits_used[f->offset + b] |= mask;
      }
      EXPECT_LE(f->min, f->max) << f->name;
      EXPECT_GT(f->lsb, 0.0) << f->name;
    }
  }
}

TEST(MessageTableTest, CyclicMessagesCarryACounterField) {
  for (const MessageSpec& s : kMessageSpecs) {
    if (!s.has_counter) continue;
    bool found = false;
    for (const FieldSpec* f : kAllFields)
      if (f->message == s.kind && std::string(f->name) == "counter") found = true;
    EXPECT_TRUE(found) << s.name;
  }
}

}  // namespace
}  // namespace vesica::fp
