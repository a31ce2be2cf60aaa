#include "device/input/input_recorder.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "device/input/input_recording.h"
#include "device/input/replay_input.h"

namespace vesica::device {
namespace {

TEST(InputRecorderTest, RecordsWritesAndReplaysTheSameFrames) {
  InputRecorder recorder("default");
  for (int i = 0; i < 50; ++i) {
    InputFrame f;
    f.time_s = i / 240.0;  // physics steps at 240 Hz: times not exact in decimal
    f.instruments[kLeft].pose.yaw_rad = 0.1 * i;
    f.instruments[kLeft].pose.insertion_m = 0.05 + 1e-4 * i;
    f.instruments[kRight].pose.roll_rad = -0.3 * i;
    f.instruments[kRight].pedal = i >= 20 && i < 30;
    recorder.Append(f);
  }
  const InputRecording& rec = recorder.recording();
  EXPECT_EQ(rec.scenario_name, "default");
  ASSERT_EQ(rec.frames.size(), 50u);

  const InputRecording back = ParseInputRecording(FormatInputRecording(rec), "recorded");
  EXPECT_EQ(back.scenario_name, "default");
  ASSERT_EQ(back.frames.size(), rec.frames.size());
  ReplayInput replay(back);
  for (const InputFrame& f : rec.frames) {
    // Replaying at the recorded times gives the recorded values bit for bit.
    const InputFrame r = replay.Sample(f.time_s);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(r.instruments[kLeft].pose.yaw_rad),
              std::bit_cast<std::uint64_t>(f.instruments[kLeft].pose.yaw_rad));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(r.instruments[kLeft].pose.insertion_m),
              std::bit_cast<std::uint64_t>(f.instruments[kLeft].pose.insertion_m));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(r.instruments[kRight].pose.roll_rad),
              std::bit_cast<std::uint64_t>(f.instruments[kRight].pose.roll_rad));
    EXPECT_EQ(r.instruments[kRight].pedal, f.instruments[kRight].pedal);
  }
}

TEST(InputRecorderTest, RejectsFramesTheFormatCannotHoldAndKeepsTheRest) {
  InputRecorder recorder;
  InputFrame f;
  f.time_s = 1.0;
  recorder.Append(f);
  EXPECT_THROW(recorder.Append(f), std::invalid_argument);  // same time
  f.time_s = 0.5;
  EXPECT_THROW(recorder.Append(f), std::invalid_argument);  // going back
  f.time_s = 2.0;
  f.instruments[kLeft].pose.pitch_rad = std::numeric_limits<double>::infinity();
  EXPECT_THROW(recorder.Append(f), std::invalid_argument);
  f.instruments[kLeft].pose.pitch_rad = 0;
  f.instruments[kRight].pose.insertion_m = -0.01;
  EXPECT_THROW(recorder.Append(f), std::invalid_argument);
  f.instruments[kRight].pose.insertion_m = 0.01;
  recorder.Append(f);
  ASSERT_EQ(recorder.recording().frames.size(), 2u);
  EXPECT_EQ(recorder.recording().frames[1].time_s, 2.0);
}

}  // namespace
}  // namespace vesica::device
