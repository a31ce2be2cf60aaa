// Seeded random-input robustness of the recording parser (a libFuzzer-free fuzz test): random
// bytes and mutated valid files either parse into a valid recording or throw RecordingError with
// a line number; no other exception, no crash (the sanitizer build runs this too).

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "device/input/input_recording.h"

namespace vesica::device {
namespace {

const std::string kValid =
    "# vesica input recording v1\n# scenario: fuzz\n"
    "time_s,left_yaw_rad,left_pitch_rad,left_roll_rad,left_insertion_m,left_jaw_rad,left_pedal,"
    "right_yaw_rad,right_pitch_rad,right_roll_rad,right_insertion_m,right_jaw_rad,right_pedal\n"
    "0,0.1,-0.2,0,0.05,0.3,0,-0.1,0.2,1.5,0.06,0,0\n"
    "0.01,0.11,-0.21,0.01,0.051,0.29,0,-0.11,0.21,1.5,0.061,0,1\n"
    "0.02,1e-3,-2.5e+2,0.02,0.052,0.28,1,-0.12,0.22,1.5,0.062,0,1\n";

// Parses and checks the outcome; returns true when the text was accepted.
bool ParseChecked(const std::string& text) {
  try {
    const InputRecording rec = ParseInputRecording(text, "fuzz.csv");
    EXPECT_FALSE(rec.frames.empty());
    for (std::size_t i = 0; i < rec.frames.size(); ++i) {
      EXPECT_FALSE(FrameProblem(rec.frames[i], i == 0 ? nullptr : &rec.frames[i - 1]).has_value());
    }
    // What was accepted formats and parses back to the same text.
    EXPECT_EQ(FormatInputRecording(ParseInputRecording(FormatInputRecording(rec), "again")), FormatInputRecording(rec));
    return true;
  } catch (const RecordingError& e) {
    EXPECT_GE(e.line(), 1) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("fuzz.csv:", 0), 0u) << e.what();
    if (e.time_s()) {
      EXPECT_TRUE(std::isfinite(*e.time_s())) << e.what();
    }
    return false;
  }
}

TEST(InputRecordingRobustnessTest, RandomBytesNeverCrash) {
  std::mt19937 rng(12345);
  for (int round = 0; round < 3000; ++round) {
    std::string text(rng() % 300, '\0');
    for (char& c : text) c = static_cast<char>(rng() & 0xff);
    if (round % 2 == 0) text = "# vesica input recording v1\n" + text;  // get past the magic line
    ParseChecked(text);
  }
}

TEST(InputRecordingRobustnessTest, MutatedValidFilesParseOrFailWithALine) {
  std::mt19937 rng(6789);
  // Bytes a mutation inserts: the format's own alphabet, so mutants get deep into the rows.
  const std::string alphabet = "0123456789.,-+eE\n\r#naif \t\x00\xff";
  int accepted = 0;
  for (int round = 0; round < 5000; ++round) {
    std::string text = kValid;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits && !text.empty(); ++k) {
      const std::size_t at = rng() % text.size();
      const char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 4) {
        case 0: text[at] = c; break;
        case 1: text.insert(text.begin() + static_cast<std::ptrdiff_t>(at), c); break;
        case 2: text.erase(at, 1 + rng() % 8); break;
        default: text.resize(at); break;
      }
    }
    if (ParseChecked(text)) ++accepted;
  }
  // Some mutants stay valid (a digit for a digit); most do not.
  EXPECT_GT(accepted, 0);
  EXPECT_LT(accepted, 5000);
}

}  // namespace
}  // namespace vesica::device
