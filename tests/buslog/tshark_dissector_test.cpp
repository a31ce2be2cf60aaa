// tshark with the generated Lua dissector against the codec: 1,000 random valid frames decode to
// the codec's message, node and field values; frames the codec refuses (remote requests, wrong
// length, a field out of range or not an enumerator, reserved bits set, fields that disagree) are marked malformed with
// the codec's error name and the field at fault; identifiers outside the plan are left alone.
// Registered only where CMake found tshark (package tshark, scripts/deps.txt).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <set>

#include "firmware_protocol/buslog/bus_log_writer.h"
#include "firmware_protocol/wireshark/codec_probe.h"
#include "firmware_protocol/wireshark/field_bits.h"
#include "firmware_protocol/wireshark/wireshark_dissector.h"
#include "random_messages.h"
#include "socketcan_pcap.h"
#include "temp_dir.h"
#include "tshark_runner.h"

namespace vesica::fp {
namespace {

bool scaled(const FieldSpec& f) { return f.lsb != 1.0 || *f.unit != '\0'; }
std::string abbrev(const FieldSpec& f) { return std::string("vesica.") + spec_of(f.message).name + "." + f.name; }
std::string qualified(const FieldSpec& f) { return std::string(spec_of(f.message).name) + "." + f.name; }

std::vector<std::string> tshark_fields() {
  std::vector<std::string> out = {"frame.number", "vesica.message", "vesica.node", "vesica.error", "vesica.error.field"};
  for (const FieldSpec* f : kAllFields) {
    out.push_back(abbrev(*f));
    if (scaled(*f)) out.push_back(abbrev(*f) + ".raw");
  }
  return out;
}

class TsharkDissectorTest : public ::testing::Test {
 protected:
  test::TempDir dir{"vesica-tshark"};
  std::filesystem::path lua = dir.path() / "vesica.lua";
  void SetUp() override { std::ofstream(lua) << wireshark_dissector_lua(); }

  std::vector<test::TsharkRow> decode_pcap(const std::vector<CanFrame>& frames) {
    const auto pcap = dir.path() / "frames.pcap";
    test::write_socketcan_pcap(pcap, frames);
    auto rows = test::run_tshark(VESICA_TSHARK, pcap, lua, tshark_fields(), dir.path());
    EXPECT_EQ(rows.size(), frames.size());
    return rows;
  }
};

std::vector<CanFrame> random_valid_frames(int n, std::mt19937& rng) {
  std::vector<CanFrame> frames;
  for (int i = 0; i < n; ++i)
    frames.push_back(test::random_valid_frame(static_cast<MessageKind>(rng() % kMessageKindCount), rng));
  return frames;
}

// Every field as the codec decoded it: raw as the table places it, SI = raw * LSB, and the value in
// the codec's struct.
void expect_same_as_codec(const CanFrame& frame, const test::TsharkRow& row) {
  Message m;
  ASSERT_EQ(decode(frame, m), DecodeError::None);
  const MessageKind kind = kind_of(m);
  SCOPED_TRACE(std::string(spec_of(kind).name) + " frame " + row.at("frame.number"));
  EXPECT_EQ(row.at("vesica.message"), spec_of(kind).name);
  EXPECT_EQ(row.at("vesica.node"), std::to_string(node_of(m)));
  EXPECT_EQ(row.at("vesica.error"), "");
  const auto codec = test::codec_field_values(m);
  for (const FieldSpec* f : kAllFields) {
    if (f->message != kind) {
      EXPECT_EQ(row.at(abbrev(*f)), "") << abbrev(*f);
      continue;
    }
    const std::int64_t raw = read_field_raw(frame, *f);
    const auto it = codec.find(f->name);
    if (scaled(*f)) {
      EXPECT_EQ(row.at(abbrev(*f) + ".raw"), std::to_string(raw)) << abbrev(*f);
      const double shown = std::stod(row.at(abbrev(*f)));
      const double si = static_cast<double>(raw) * f->lsb;
      EXPECT_NEAR(shown, si, 1e-12 * std::max(1.0, std::fabs(si))) << abbrev(*f);
      if (it != codec.end()) {
        EXPECT_FLOAT_EQ(static_cast<float>(shown), static_cast<float>(it->second)) << abbrev(*f);
      }
    } else {
      EXPECT_EQ(row.at(abbrev(*f)), std::to_string(raw)) << abbrev(*f);
      if (it != codec.end()) {
        EXPECT_EQ(static_cast<double>(raw), it->second) << abbrev(*f);
      }
    }
  }
}

TEST_F(TsharkDissectorTest, ThousandRandomValidFramesDecodeToTheCodecsValues) {
  std::mt19937 rng(1000);
  const std::vector<CanFrame> frames = random_valid_frames(1000, rng);
  std::set<std::string> kinds_seen;
  const auto rows = decode_pcap(frames);
  ASSERT_EQ(rows.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    expect_same_as_codec(frames[i], rows[i]);
    kinds_seen.insert(rows[i].at("vesica.message"));
  }
  EXPECT_EQ(kinds_seen.size(), kMessageKindCount);  // every message of the table was decoded
}

TEST_F(TsharkDissectorTest, TsharkReadsOurBusLogWithTheDissector) {
  std::mt19937 rng(2000);
  const std::vector<CanFrame> frames = random_valid_frames(200, rng);
  const auto log_path = dir.path() / "session.log";
  {
    std::ofstream file(log_path);
    BusLogWriter log(file);
    for (std::size_t i = 0; i < frames.size(); ++i)
      log.write({Nanoseconds{1700000000000000000LL + static_cast<long long>(i) * 1000000}, "can0", frames[i]});
  }
  const auto rows = test::run_tshark(VESICA_TSHARK, log_path, lua, tshark_fields(), dir.path());
  ASSERT_EQ(rows.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) expect_same_as_codec(frames[i], rows[i]);
}

struct Malformed {
  CanFrame frame;
  DecodeError codec;       // what decode() says
  std::string field;       // the field the dissector must name ("" = any field of the message)
  int mutated_byte = -1;   // for random mutations: the named field must cover this byte
};

std::int64_t wire_min(const FieldSpec& f) {
  if (f.bit_width) return 0;
  return is_signed(f.type) ? -(std::int64_t{1} << (8 * wire_size(f.type) - 1)) : 0;
}
std::int64_t wire_max(const FieldSpec& f) {
  if (f.bit_width) return (std::int64_t{1} << f.bit_width) - 1;
  return is_signed(f.type) ? (std::int64_t{1} << (8 * wire_size(f.type) - 1)) - 1 : (std::int64_t{1} << (8 * wire_size(f.type))) - 1;
}

std::vector<Malformed> malformed_frames(std::mt19937& rng) {
  std::vector<Malformed> out;
  for (const MessageSpec& s : kMessageSpecs) {  // each message as a remote request, one byte short and one too long
    CanFrame f = test::random_valid_frame(s.kind, rng);
    CanFrame rtr = f;
    rtr.flags |= CanFrame::kRemote;
    out.push_back({rtr, DecodeError::RemoteFrame, ""});
    f.len = static_cast<std::uint8_t>(s.length - 1);
    out.push_back({f, DecodeError::WrongLength, ""});
    f.len = static_cast<std::uint8_t>(s.length == 8 ? 0 : s.length + 1);
    out.push_back({f, DecodeError::WrongLength, ""});
  }
  for (const FieldSpec* fs : kAllFields) {  // every field just outside its range, where the wire allows
    for (const std::int64_t raw : {raw_min(*fs) - 1, raw_max(*fs) + 1}) {
      if (raw < wire_min(*fs) || raw > wire_max(*fs)) continue;
      CanFrame f = test::random_valid_frame(fs->message, rng);
      write_field_raw(f, *fs, raw);
      out.push_back({f, DecodeError::OutOfRange, qualified(*fs)});
    }
  }
  for (const MessageSpec& s : kMessageSpecs) {  // values inside the range that are no enumerator; reserved bits
    const CodecProbe probe = probe_codec(s.kind);
    for (const FieldEnumeration& e : probe.enumerations) {
      for (std::int64_t raw = raw_min(*e.field); raw <= raw_max(*e.field); ++raw) {
        if (std::find(e.valid_raw.begin(), e.valid_raw.end(), raw) != e.valid_raw.end()) continue;
        CanFrame f = test::random_valid_frame(s.kind, rng);
        write_field_raw(f, *e.field, raw);
        out.push_back({f, DecodeError::OutOfRange, qualified(*e.field)});
      }
    }
    for (const ReservedBits& r : probe.reserved) {
      for (int bit = 0; bit < 8; ++bit) {
        if (!(r.mask & (1 << bit))) continue;
        CanFrame f = test::random_valid_frame(s.kind, rng);
        f.data[r.offset] = static_cast<std::uint8_t>(f.data[r.offset] | (1 << bit));
        out.push_back({f, DecodeError::OutOfRange, std::string(s.name) + ".reserved" + std::to_string(r.offset)});
      }
    }
  }
  {  // fields that disagree: the codec's three cross-field rules
    CanFrame f = test::random_valid_frame(MessageKind::Emergency, rng);
    write_field_raw(f, fields::Emergency::fault, (read_field_raw(f, fields::Emergency::fault) + 1) % kFaultCodeCount);
    out.push_back({f, DecodeError::Inconsistent, "Emergency.error_code"});
    f = test::random_valid_frame(MessageKind::Heartbeat, rng);
    write_field_raw(f, fields::Heartbeat::canopen_state, 0x01);  // no node state reports 1
    out.push_back({f, DecodeError::Inconsistent, "Heartbeat.canopen_state"});
    f = test::random_valid_frame(MessageKind::Identity, rng);
    write_field_raw(f, fields::Identity::min_minor, 9);
    write_field_raw(f, fields::Identity::max_minor, 8);
    out.push_back({f, DecodeError::Inconsistent, "Identity.min_minor"});
  }
  for (int i = 0; i < 300; ++i) {  // one random byte changed: whatever the codec says
    const auto kind = static_cast<MessageKind>(rng() % kMessageKindCount);
    CanFrame f = test::random_valid_frame(kind, rng);
    const int byte = static_cast<int>(rng() % f.len);
    f.data[byte] = static_cast<std::uint8_t>(rng());
    Message m;
    out.push_back({f, decode(f, m), "", byte});
  }
  return out;
}

std::vector<std::string> split(const std::string& joined) {  // tshark joins occurrences with ','
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < joined.size()) {
    const std::size_t comma = joined.find(',', start);
    out.push_back(joined.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

bool covers(const FieldSpec& f, int byte) {
  return byte >= f.offset && byte < f.offset + wire_size(f.type);
}

TEST_F(TsharkDissectorTest, MalformedFramesAreNamedAsTheCodecRefusesThem) {
  std::mt19937 rng(3000);
  const std::vector<Malformed> cases = malformed_frames(rng);
  std::vector<CanFrame> frames;
  for (const Malformed& c : cases) frames.push_back(c.frame);
  // Identifiers outside the plan: not ours, so the dissector leaves them to Wireshark.
  std::vector<CanFrame> foreign;
  while (foreign.size() < 20) {
    CanFrame f;
    f.id = rng() & 0x7FF;
    f.len = 8;
    MessageKind kind;
    std::uint8_t node;
    if (!classify_id(f.id, kind, node)) foreign.push_back(f);
  }
  frames.insert(frames.end(), foreign.begin(), foreign.end());
  const auto rows = decode_pcap(frames);
  ASSERT_EQ(rows.size(), frames.size());

  std::map<DecodeError, int> counted;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Malformed& c = cases[i];
    const test::TsharkRow& row = rows[i];
    Message m;
    ASSERT_EQ(decode(c.frame, m), c.codec) << "frame " << i + 1;  // the case is what the codec says
    ++counted[c.codec];
    MessageKind kind;
    std::uint8_t node;
    ASSERT_TRUE(classify_id(c.frame.id, kind, node));
    SCOPED_TRACE("frame " + row.at("frame.number") + " " + spec_of(kind).name + " expected " + to_string(c.codec) + " " + c.field);
    EXPECT_EQ(row.at("vesica.message"), spec_of(kind).name);
    if (c.codec == DecodeError::None) {
      EXPECT_EQ(row.at("vesica.error"), "");
      continue;
    }
    if (c.codec == DecodeError::WrongLength || c.codec == DecodeError::RemoteFrame) {
      EXPECT_EQ(row.at("vesica.error"), to_string(c.codec));
      EXPECT_EQ(row.at("vesica.error.field"), "");
      continue;
    }
    if (!c.field.empty()) {  // one field set wrong on purpose: that one error, that field
      EXPECT_EQ(row.at("vesica.error"), to_string(c.codec));
      EXPECT_EQ(row.at("vesica.error.field"), c.field);
      continue;
    }
    // A random byte: every error is the codec's; an out-of-range field holds the changed byte (a
    // byte may break two fields at once, e.g. a state and the reserved bits beside it).
    for (const std::string& error : split(row.at("vesica.error"))) EXPECT_EQ(error, to_string(c.codec));
    const std::vector<std::string> named = split(row.at("vesica.error.field"));
    ASSERT_FALSE(named.empty());
    for (const std::string& name : named) {
      if (c.codec == DecodeError::Inconsistent) {
        EXPECT_EQ(name.rfind(std::string(spec_of(kind).name) + ".", 0), 0u) << name;
        continue;
      }
      bool holds = name == std::string(spec_of(kind).name) + ".reserved" + std::to_string(c.mutated_byte);
      for (const FieldSpec* f : kAllFields)
        if (f->message == kind && covers(*f, c.mutated_byte) && name == qualified(*f)) holds = true;
      EXPECT_TRUE(holds) << name << " does not hold byte " << c.mutated_byte;
    }
  }
  for (std::size_t i = cases.size(); i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].at("vesica.message"), "") << "foreign id " << frames[i].id;
    EXPECT_EQ(rows[i].at("vesica.error"), "");
  }
  // Every way the codec refuses a frame was exercised.
  EXPECT_GE(counted[DecodeError::WrongLength], 2 * static_cast<int>(kMessageKindCount));
  EXPECT_EQ(counted[DecodeError::RemoteFrame], static_cast<int>(kMessageKindCount));
  EXPECT_GT(counted[DecodeError::OutOfRange], 0);
  EXPECT_GT(counted[DecodeError::Inconsistent], 0);
  EXPECT_GT(counted[DecodeError::None], 0);
}

}  // namespace
}  // namespace vesica::fp
