// The right port's tool in a recording (v2): exchanges round-trip, recordings without one stay
// v1 byte for byte, and a bad tool is refused naming line and column.
#include <gtest/gtest.h>

#include <string>

#include "device/input/input_frame.h"
#include "device/input/input_recording.h"
#include "device/input/replay_input.h"

namespace vesica::device {
namespace {

using physics::InstrumentTool;

constexpr const char* kV1 =
    "# vesica input recording v1\n"
    "time_s,left_yaw_rad,left_pitch_rad,left_roll_rad,left_insertion_m,left_jaw_rad,left_pedal,"
    "right_yaw_rad,right_pitch_rad,right_roll_rad,right_insertion_m,right_jaw_rad,right_pedal\n"
    "0,0.1,-0.2,0,0.05,0.3,0,-0.1,0.2,1.5,0.06,0,1\n"
    "0.01,0.11,-0.21,0.01,0.051,0.29,0,-0.11,0.21,1.5,0.061,0,0\n";

constexpr const char* kV2Head =
    "# vesica input recording v2\n# scenario: calot\n"
    "time_s,left_yaw_rad,left_pitch_rad,left_roll_rad,left_insertion_m,left_jaw_rad,left_pedal,"
    "right_yaw_rad,right_pitch_rad,right_roll_rad,right_insertion_m,right_jaw_rad,right_pedal,right_tool\n";

InputRecording ExchangingRecording() {
  InputRecording rec;
  rec.scenario_name = "calot";
  const InstrumentTool tools[] = {InstrumentTool::kCauteryHook, InstrumentTool::kClipApplier,
                                  InstrumentTool::kClipApplier, InstrumentTool::kScissors};
  for (int i = 0; i < 4; ++i) {
    InputFrame f;
    f.time_s = 0.005 * i;
    f.instruments[kRight].pose.insertion_m = 0.08 + 0.001 * i;
    f.instruments[kRight].pose.jaw_angle_rad = i == 2 ? 0.0 : 0.4;
    f.right_tool = tools[i];
    rec.frames.push_back(f);
  }
  return rec;
}

TEST(InstrumentExchangeRecording, AFrameStartsWithTheHookInTheRightPort) {
  const InputFrame f;
  EXPECT_EQ(f.right_tool, InstrumentTool::kCauteryHook);
  EXPECT_FALSE(FrameProblem(f, nullptr).has_value());
}

TEST(InstrumentExchangeRecording, ExchangesRoundTripAsV2) {
  const InputRecording rec = ExchangingRecording();
  const std::string text = FormatInputRecording(rec);
  EXPECT_EQ(text.rfind(kV2Head, 0), 0u) << text;
  EXPECT_NE(text.find(",0,clip_applier\n"), std::string::npos) << text;
  const InputRecording back = ParseInputRecording(text, "x.csv");
  ASSERT_EQ(back.frames.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(back.frames[i].right_tool, rec.frames[i].right_tool) << i;
  }
  EXPECT_EQ(FormatInputRecording(back), text);
}

TEST(InstrumentExchangeRecording, AHookOnlyRecordingStaysV1ByteForByte) {
  const InputRecording rec = ParseInputRecording(kV1, "v1.csv");
  for (const InputFrame& f : rec.frames) EXPECT_EQ(f.right_tool, InstrumentTool::kCauteryHook);
  EXPECT_EQ(FormatInputRecording(rec), kV1);
}

TEST(InstrumentExchangeRecording, ABadToolIsRefusedNamingLineAndValue) {
  const auto expect_error = [](const std::string& tail, int line, const std::string& fragment) {
    try {
      ParseInputRecording(std::string(kV2Head) + tail, "rec.csv");
      ADD_FAILURE() << "accepted " << tail;
    } catch (const RecordingError& e) {
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error("0,0,0,0,0.05,0,0,0,0,0,0.05,0,0,grasper\n", 4,
               "right_tool must be cautery_hook, clip_applier or scissors, found 'grasper'");
  expect_error("0,0,0,0,0.05,0,0,0,0,0,0.05,0,0,laser\n", 4, "found 'laser'");
  expect_error("0,0,0,0,0.05,0,0,0,0,0,0.05,0,0\n", 4, "row has 13 fields, expected 14");
  expect_error("0,0,0,0,0.05,0,0,0,0,0,0.05,0,0,scissors,1\n", 4, "row has 15 fields, expected 14");
}

TEST(InstrumentExchangeRecording, TheGrasperInTheRightPortIsAFrameProblem) {
  InputFrame f;
  f.right_tool = InstrumentTool::kGrasper;
  EXPECT_EQ(FrameProblem(f, nullptr).value_or(""), "the right port holds the grasper");
  InputRecording rec;
  rec.frames.push_back(f);
  EXPECT_THROW(FormatInputRecording(rec), std::invalid_argument);
}

TEST(InstrumentExchangeRecording, ReplayHoldsEachFramesToolUntilTheNext) {
  ReplayInput replay(ExchangingRecording());
  EXPECT_EQ(replay.Sample(0.004).right_tool, InstrumentTool::kCauteryHook);
  EXPECT_EQ(replay.Sample(0.005).right_tool, InstrumentTool::kClipApplier);
  EXPECT_EQ(replay.Sample(0.0149).right_tool, InstrumentTool::kClipApplier);
  EXPECT_EQ(replay.Sample(1.0).right_tool, InstrumentTool::kScissors);
  EXPECT_EQ(replay.Sample(0.0).right_tool, InstrumentTool::kCauteryHook);
}

}  // namespace
}  // namespace vesica::device
