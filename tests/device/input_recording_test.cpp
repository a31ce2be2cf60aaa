#include "device/input/input_recording.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

namespace vesica::device {
namespace {

constexpr const char* kHeader =
    "time_s,left_yaw_rad,left_pitch_rad,left_roll_rad,left_insertion_m,left_jaw_rad,left_pedal,"
    "right_yaw_rad,right_pitch_rad,right_roll_rad,right_insertion_m,right_jaw_rad,right_pedal\n";

// A small valid recording: magic (line 1), scenario (2), header (3), rows at lines 4..7.
std::string ValidText() {
  return std::string("# vesica input recording v1\n# scenario: default\n") + kHeader +
         "0,0.1,-0.2,0,0.05,0.3,0,-0.1,0.2,1.5,0.06,0,0\n"
         "0.01,0.11,-0.21,0.01,0.051,0.29,0,-0.11,0.21,1.5,0.061,0,1\n"
         "0.02,0.12,-0.22,0.02,0.052,0.28,1,-0.12,0.22,1.5,0.062,0,1\n"
         "0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n";
}

// Valid text whose 4th frame (line 7) is replaced by `row`.
std::string WithLastRow(const std::string& row) {
  std::string text = ValidText();
  const std::size_t last = text.rfind('\n', text.size() - 2) + 1;
  return text.substr(0, last) + row;
}

double RandomDouble(std::mt19937_64& rng) {
  // Mix of ordinary magnitudes, extremes and arbitrary finite bit patterns.
  switch (rng() % 4) {
    case 0: return std::uniform_real_distribution<double>(-3.5, 3.5)(rng);
    case 1: return std::ldexp(std::uniform_real_distribution<double>(-1, 1)(rng), static_cast<int>(rng() % 2000) - 1000);
    case 2: {
      static constexpr double kEdges[] = {0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308,
                                          1.7976931348623157e308, -1.7976931348623157e308, 0.1, 1.0 / 3.0};
      return kEdges[rng() % std::size(kEdges)];
    }
    default: {
      for (;;) {
        const double d = std::bit_cast<double>(static_cast<std::uint64_t>(rng()));
        if (std::isfinite(d)) return d;
      }
    }
  }
}

InputRecording RandomRecording(std::mt19937_64& rng, int frames) {
  InputRecording rec;
  rec.scenario_name = "random, with spaces: and # signs";
  double t = -1.0;
  for (int i = 0; i < frames; ++i) {
    InputFrame f;
    t = std::nextafter(t, 1e9) + std::uniform_real_distribution<double>(0, 0.01)(rng);
    f.time_s = t;
    for (InstrumentInput& in : f.instruments) {
      in.pose.yaw_rad = RandomDouble(rng);
      in.pose.pitch_rad = RandomDouble(rng);
      in.pose.roll_rad = RandomDouble(rng);
      in.pose.insertion_m = std::abs(RandomDouble(rng));
      in.pose.jaw_angle_rad = RandomDouble(rng);
      in.pedal = rng() % 2 == 1;
    }
    rec.frames.push_back(f);
  }
  return rec;
}

void ExpectBitIdentical(double a, double b) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b)) << a << " vs " << b;
}

void ExpectSameRecording(const InputRecording& a, const InputRecording& b) {
  EXPECT_EQ(a.scenario_name, b.scenario_name);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    ExpectBitIdentical(a.frames[i].time_s, b.frames[i].time_s);
    EXPECT_EQ(a.frames[i].right_tool, b.frames[i].right_tool);
    for (int s = 0; s < 2; ++s) {
      const InstrumentInput& x = a.frames[i].instruments[s];
      const InstrumentInput& y = b.frames[i].instruments[s];
      ExpectBitIdentical(x.pose.yaw_rad, y.pose.yaw_rad);
      ExpectBitIdentical(x.pose.pitch_rad, y.pose.pitch_rad);
      ExpectBitIdentical(x.pose.roll_rad, y.pose.roll_rad);
      ExpectBitIdentical(x.pose.insertion_m, y.pose.insertion_m);
      ExpectBitIdentical(x.pose.jaw_angle_rad, y.pose.jaw_angle_rad);
      EXPECT_EQ(x.pedal, y.pedal);
    }
  }
}

// Parses `text` expecting a RecordingError at `line`, whose message contains `fragment` and,
// when `time` is given, "(t=TIME s)".
void ExpectError(const std::string& text, int line, const char* time, const std::string& fragment) {
  try {
    ParseInputRecording(text, "rec.csv");
    ADD_FAILURE() << "accepted, expected an error at line " << line << " containing " << fragment;
  } catch (const RecordingError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.line(), line) << what;
    const std::string prefix = "rec.csv:" + std::to_string(line) + (time ? std::string(" (t=") + time + " s): " : ": ");
    EXPECT_EQ(what.rfind(prefix, 0), 0u) << "message '" << what << "' does not start with '" << prefix << "'";
    EXPECT_NE(what.find(fragment), std::string::npos) << "message '" << what << "' lacks '" << fragment << "'";
    EXPECT_EQ(e.time_s().has_value(), time != nullptr) << what;
  }
}

TEST(InputRecordingTest, ParsesTheDocumentedExample) {
  const InputRecording rec = ParseInputRecording(ValidText(), "rec.csv");
  EXPECT_EQ(rec.scenario_name, "default");
  ASSERT_EQ(rec.frames.size(), 4u);
  const InputFrame& f = rec.frames[1];
  EXPECT_EQ(f.time_s, 0.01);
  EXPECT_EQ(f.instruments[kLeft].pose.yaw_rad, 0.11);
  EXPECT_EQ(f.instruments[kLeft].pose.pitch_rad, -0.21);
  EXPECT_EQ(f.instruments[kLeft].pose.roll_rad, 0.01);
  EXPECT_EQ(f.instruments[kLeft].pose.insertion_m, 0.051);
  EXPECT_EQ(f.instruments[kLeft].pose.jaw_angle_rad, 0.29);
  EXPECT_FALSE(f.instruments[kLeft].pedal);
  EXPECT_EQ(f.instruments[kRight].pose.yaw_rad, -0.11);
  EXPECT_EQ(f.instruments[kRight].pose.pitch_rad, 0.21);
  EXPECT_EQ(f.instruments[kRight].pose.roll_rad, 1.5);
  EXPECT_EQ(f.instruments[kRight].pose.insertion_m, 0.061);
  EXPECT_EQ(f.instruments[kRight].pose.jaw_angle_rad, 0.0);
  EXPECT_TRUE(f.instruments[kRight].pedal);
  EXPECT_TRUE(rec.frames[2].instruments[kLeft].pedal);
}

// The example in docs/recording.md is a valid recording (keeps the page honest).
TEST(InputRecordingTest, DocsExampleParses) {
  std::ifstream doc(std::string(VESICA_SOURCE_DIR) + "/docs/recording.md");
  ASSERT_TRUE(doc) << "docs/recording.md not found";
  std::string line, example;
  bool inside = false;
  while (std::getline(doc, line)) {
    if (line == "    # vesica input recording v1") inside = true;
    if (inside && line.rfind("    ", 0) != 0) break;
    if (inside) example += line.substr(4) + "\n";
  }
  const InputRecording rec = ParseInputRecording(example, "docs/recording.md");
  EXPECT_EQ(rec.scenario_name, "cholecystectomy");
  ASSERT_EQ(rec.frames.size(), 4u);
  EXPECT_EQ(rec.frames[1].time_s, 0.005);
  EXPECT_EQ(rec.frames[1].instruments[kLeft].pose.jaw_angle_rad, 0.15);
  EXPECT_TRUE(rec.frames[1].instruments[kRight].pedal);
  EXPECT_FALSE(rec.frames[3].instruments[kRight].pedal);
}

TEST(InputRecordingTest, FormatIsTheDocumentedText) {
  const InputRecording rec = ParseInputRecording(ValidText(), "rec.csv");
  EXPECT_EQ(FormatInputRecording(rec), ValidText());
}

TEST(InputRecordingTest, ScenarioLineIsOptionalAndOtherCommentsAreIgnored) {
  const std::string text = std::string("# vesica input recording v1\n# recorded on the ward trainer\n") + kHeader +
                           "0,0,0,0,0,0,0,0,0,0,0,0,0\n";
  const InputRecording rec = ParseInputRecording(text, "rec.csv");
  EXPECT_EQ(rec.scenario_name, "");
  EXPECT_EQ(rec.frames.size(), 1u);
  // Without a scenario the writer writes no scenario line.
  EXPECT_EQ(FormatInputRecording(rec), std::string("# vesica input recording v1\n") + kHeader +
                                           "0,0,0,0,0,0,0,0,0,0,0,0,0\n");
}

TEST(InputRecordingTest, AcceptsCrlfLineEnds) {
  std::string text;
  for (char c : ValidText()) {
    if (c == '\n') text += '\r';
    text += c;
  }
  ExpectSameRecording(ParseInputRecording(text, "rec.csv"), ParseInputRecording(ValidText(), "rec.csv"));
}

TEST(InputRecordingTest, RandomFramesRoundTripBitIdenticalThroughAFile) {
  std::mt19937_64 rng(20261123);
  const InputRecording rec = RandomRecording(rng, 500);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "vesica_input_recording_roundtrip.csv";
  WriteInputRecording(file, rec);
  const InputRecording back = ReadInputRecording(file);
  std::filesystem::remove(file);
  ExpectSameRecording(rec, back);
  // And the text is a fixed point: formatting what was read gives the same bytes.
  EXPECT_EQ(FormatInputRecording(back), FormatInputRecording(rec));
}

TEST(InputRecordingTest, WriterRejectsWhatTheReaderWould) {
  InputRecording rec = ParseInputRecording(ValidText(), "rec.csv");
  InputRecording bad = rec;
  bad.frames.clear();
  EXPECT_THROW(FormatInputRecording(bad), std::invalid_argument);
  bad = rec;
  bad.scenario_name = "two\nlines";
  EXPECT_THROW(FormatInputRecording(bad), std::invalid_argument);
  bad = rec;
  bad.frames[2].time_s = bad.frames[1].time_s;
  EXPECT_THROW(FormatInputRecording(bad), std::invalid_argument);
  bad = rec;
  bad.frames[0].instruments[kRight].pose.jaw_angle_rad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(FormatInputRecording(bad), std::invalid_argument);
  bad = rec;
  bad.frames[3].instruments[kLeft].pose.insertion_m = -1e-3;
  EXPECT_THROW(FormatInputRecording(bad), std::invalid_argument);
}

TEST(InputRecordingTest, RejectsAMissingOrWrongMagicLine) {
  ExpectError("", 1, nullptr, "empty file");
  ExpectError(kHeader, 1, nullptr, "not an input recording");
  ExpectError(std::string("# vesica input recording v3\n") + kHeader, 1, nullptr,
              "unsupported recording version 'v3', this build reads v1 and v2");
  ExpectError("\xef\xbb\xbf# vesica input recording v1\n", 1, nullptr, "'\\xef\\xbb\\xbf# vesica");
}

TEST(InputRecordingTest, RejectsAWrongHeaderNamingTheFirstWrongColumn) {
  const std::string magic = "# vesica input recording v1\n# scenario: x\n";
  std::string header = kHeader;
  header.replace(header.find("left_insertion_m"), 16, "left_insert_mm");
  ExpectError(magic + header, 3, nullptr, "header column 5 is 'left_insert_mm', expected 'left_insertion_m'");
  ExpectError(magic + "time_s,left_yaw_rad\n", 3, nullptr, "header ends after column 2, expected 'left_pitch_rad'");
  std::string extra = kHeader;
  extra.insert(extra.size() - 1, ",force_n");
  ExpectError(magic + extra, 3, nullptr, "extra column 14 'force_n'");
  ExpectError(magic, 3, nullptr, "missing header line");
  ExpectError(magic + "# scenario: y\n" + kHeader, 3, nullptr, "second '# scenario:' line");
}

TEST(InputRecordingTest, RejectsNoFrames) {
  ExpectError(std::string("# vesica input recording v1\n") + kHeader, 2, nullptr, "no frames");
}

TEST(InputRecordingTest, RejectsTooFewFieldsNamingTheLastGoodRow) {
  // A row cut after its 3rd field: its own time parsed, the message points back to line 6.
  ExpectError(WithLastRow("0.03,0.13,-0.23\n"), 7, "0.03",
              "row has 3 fields, expected 13 (file truncated?); last good row: line 6, t=0.02 s");
  // A row with an unreadable time carries the last good row's time.
  ExpectError(WithLastRow("\n"), 7, "0.02", "row has 1 field, expected 13");
  // Too few fields in the first row: no good row and no time yet.
  ExpectError(std::string("# vesica input recording v1\n") + kHeader + "x,1\n", 3, nullptr,
              "row has 2 fields, expected 13 (file truncated?); no good row before it");
}

TEST(InputRecordingTest, RejectsTooManyFields) {
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0,7\n"), 7, "0.03",
              "row has 14 fields, expected 13; last good row: line 6, t=0.02 s");
}

TEST(InputRecordingTest, RejectsAMissingFinalNewline) {
  // All 13 fields but no line end: the file was cut, the row is not trusted.
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0"), 7, "0.02",
              "truncated; last good row: line 6, t=0.02 s");
}

TEST(InputRecordingTest, RejectsNonNumbers) {
  ExpectError(WithLastRow("0.03,0.13,-0.23,abc,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "left_roll_rad 'abc' is not a number");
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13, 0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "right_pitch_rad ' 0.23' is not a number");
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,+1.5,0.063,0,0\n"), 7, "0.03",
              "right_roll_rad '+1.5' is not a number");
  ExpectError(WithLastRow("0.03,0.13,1e,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "left_pitch_rad '1e' is not a number");
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "left_jaw_rad is empty");
  ExpectError(WithLastRow("0.03,1e999,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "left_yaw_rad '1e999' is out of range");
  // The time itself unreadable: the message carries the previous row's time.
  ExpectError(WithLastRow("0.03s,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.02",
              "time_s '0.03s' is not a number");
}

TEST(InputRecordingTest, RejectsNanAndInf) {
  ExpectError(WithLastRow("0.03,nan,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "left_yaw_rad 'nan' is not finite");
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,inf,0,0\n"), 7, "0.03",
              "right_insertion_m 'inf' is not finite");
  ExpectError(WithLastRow("-inf,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.02",
              "time_s '-inf' is not finite");
}

TEST(InputRecordingTest, RejectsAPedalOtherThanZeroOrOne) {
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,2,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "left_pedal must be 0 or 1, found '2'");
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,1.0\n"), 7, "0.03",
              "right_pedal must be 0 or 1, found '1.0'");
}

TEST(InputRecordingTest, RejectsTimeNotStrictlyIncreasing) {
  ExpectError(WithLastRow("0.02,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.02",
              "time_s 0.02 is not after the previous row's 0.02 (line 6)");
  ExpectError(WithLastRow("0.015,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.015",
              "time_s 0.015 is not after the previous row's 0.02 (line 6)");
}

TEST(InputRecordingTest, RejectsNegativeInsertion) {
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,-0.001,0.27,1,-0.13,0.23,1.5,0.063,0,0\n"), 7, "0.03",
              "left_insertion_m is negative ('-0.001')");
  ExpectError(WithLastRow("0.03,0.13,-0.23,0.03,0.053,0.27,1,-0.13,0.23,1.5,-1e-9,0,0\n"), 7, "0.03",
              "right_insertion_m is negative ('-1e-9')");
}

TEST(InputRecordingTest, UnreadableFileNamesThePath) {
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "vesica_no_such_recording.csv";
  std::filesystem::remove(missing);
  try {
    ReadInputRecording(missing);
    ADD_FAILURE() << "read a missing file";
  } catch (const RecordingError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
  }
  try {
    ReadInputRecording(std::filesystem::temp_directory_path());
    ADD_FAILURE() << "read a directory";
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
}

TEST(InputRecordingTest, ReadFileErrorsNameTheFileAndLine) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "vesica_bad_recording.csv";
  std::ofstream(file, std::ios::binary) << WithLastRow("0.03,0.13\n");
  try {
    ReadInputRecording(file);
    ADD_FAILURE() << "accepted a truncated file";
  } catch (const RecordingError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(file.string() + ":7 (t=0.03 s): ", 0), 0u) << e.what();
  }
  std::filesystem::remove(file);
}

// A valid file cut at every byte: either a valid prefix (only when the cut falls just after a
// line end and at least one row is whole) or an error with a line number, never anything else.
TEST(InputRecordingTest, TruncationAtEveryByteIsAPrefixOrALineError) {
  std::mt19937_64 rng(7);
  const InputRecording full = RandomRecording(rng, 6);
  const std::string text = FormatInputRecording(full);
  const std::size_t header_end = text.find('\n', text.find("time_s")) + 1;
  int accepted = 0;
  for (std::size_t cut = 0; cut <= text.size(); ++cut) {
    const std::string part = text.substr(0, cut);
    const bool at_line_end = cut > header_end && text[cut - 1] == '\n';
    try {
      const InputRecording rec = ParseInputRecording(part, "cut.csv");
      ASSERT_TRUE(at_line_end) << "accepted a cut at byte " << cut;
      const auto rows = static_cast<std::size_t>(std::count(text.begin() + header_end, text.begin() + cut, '\n'));
      InputRecording expected = full;
      expected.frames.resize(rows);
      ExpectSameRecording(rec, expected);
      ++accepted;
    } catch (const RecordingError& e) {
      EXPECT_FALSE(at_line_end) << "rejected a whole-line prefix at byte " << cut << ": " << e.what();
      EXPECT_GE(e.line(), 1) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("cut.csv:" + std::to_string(e.line()), 0), 0u) << e.what();
    }
  }
  EXPECT_EQ(accepted, 6);
}

}  // namespace
}  // namespace vesica::device
