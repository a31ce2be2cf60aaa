#include "device/input/replay_input.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace vesica::device {
namespace {

InputFrame Frame(double t, double left_yaw, double left_insertion, bool left_pedal, double right_roll,
                 double right_jaw, bool right_pedal) {
  InputFrame f;
  f.time_s = t;
  f.instruments[kLeft].pose.yaw_rad = left_yaw;
  f.instruments[kLeft].pose.pitch_rad = -left_yaw;
  f.instruments[kLeft].pose.insertion_m = left_insertion;
  f.instruments[kLeft].pedal = left_pedal;
  f.instruments[kRight].pose.roll_rad = right_roll;
  f.instruments[kRight].pose.jaw_angle_rad = right_jaw;
  f.instruments[kRight].pedal = right_pedal;
  return f;
}

// Frames at t = 1, 3, 4 s with values chosen so the interpolants are exact in binary.
InputRecording ThreeFrames() {
  InputRecording rec;
  rec.scenario_name = "hand";
  rec.frames = {Frame(1.0, 2.0, 0.0, false, 0.0, 0.5, true),  //
                Frame(3.0, 6.0, 0.04, true, -1.0, 0.25, false),
                Frame(4.0, 5.0, 0.02, false, 3.0, 0.25, true)};
  return rec;
}

TEST(ReplayInputTest, InterpolatesContinuousChannelsLinearly) {
  ReplayInput replay(ThreeFrames());
  // t = 1.5: a quarter of the way from frame 0 to frame 1.
  InputFrame f = replay.Sample(1.5);
  EXPECT_EQ(f.time_s, 1.5);
  EXPECT_DOUBLE_EQ(f.instruments[kLeft].pose.yaw_rad, 3.0);
  EXPECT_DOUBLE_EQ(f.instruments[kLeft].pose.pitch_rad, -3.0);
  EXPECT_DOUBLE_EQ(f.instruments[kLeft].pose.insertion_m, 0.01);
  EXPECT_DOUBLE_EQ(f.instruments[kRight].pose.roll_rad, -0.25);
  EXPECT_DOUBLE_EQ(f.instruments[kRight].pose.jaw_angle_rad, 0.4375);
  // t = 3.5: halfway from frame 1 to frame 2.
  f = replay.Sample(3.5);
  EXPECT_DOUBLE_EQ(f.instruments[kLeft].pose.yaw_rad, 5.5);
  EXPECT_DOUBLE_EQ(f.instruments[kLeft].pose.insertion_m, 0.03);
  EXPECT_DOUBLE_EQ(f.instruments[kRight].pose.roll_rad, 1.0);
  EXPECT_DOUBLE_EQ(f.instruments[kRight].pose.jaw_angle_rad, 0.25);
  // Untouched channels stay 0.
  EXPECT_EQ(f.instruments[kRight].pose.yaw_rad, 0.0);
  EXPECT_EQ(f.instruments[kRight].pose.insertion_m, 0.0);
}

TEST(ReplayInputTest, HitsRecordedFramesExactly) {
  const InputRecording rec = ThreeFrames();
  ReplayInput replay(rec);
  for (const InputFrame& want : rec.frames) {
    const InputFrame got = replay.Sample(want.time_s);
    EXPECT_EQ(got.instruments[kLeft].pose.yaw_rad, want.instruments[kLeft].pose.yaw_rad);
    EXPECT_EQ(got.instruments[kLeft].pose.insertion_m, want.instruments[kLeft].pose.insertion_m);
    EXPECT_EQ(got.instruments[kRight].pose.roll_rad, want.instruments[kRight].pose.roll_rad);
    EXPECT_EQ(got.instruments[kLeft].pedal, want.instruments[kLeft].pedal);
    EXPECT_EQ(got.instruments[kRight].pedal, want.instruments[kRight].pedal);
  }
}

TEST(ReplayInputTest, PedalHoldsTheFrameAtOrBefore) {
  ReplayInput replay(ThreeFrames());
  EXPECT_FALSE(replay.Sample(1.0).instruments[kLeft].pedal);
  EXPECT_FALSE(replay.Sample(2.999).instruments[kLeft].pedal);  // not yet pressed at frame 1
  EXPECT_TRUE(replay.Sample(3.0).instruments[kLeft].pedal);
  EXPECT_TRUE(replay.Sample(3.999).instruments[kLeft].pedal);
  EXPECT_FALSE(replay.Sample(4.0).instruments[kLeft].pedal);
  EXPECT_TRUE(replay.Sample(2.0).instruments[kRight].pedal);
  EXPECT_FALSE(replay.Sample(3.5).instruments[kRight].pedal);
  EXPECT_TRUE(replay.Sample(4.0).instruments[kRight].pedal);
}

TEST(ReplayInputTest, ClampsBeforeTheFirstAndAfterTheLastFrame) {
  ReplayInput replay(ThreeFrames());
  const InputFrame before = replay.Sample(-10.0);
  EXPECT_EQ(before.time_s, -10.0);
  EXPECT_EQ(before.instruments[kLeft].pose.yaw_rad, 2.0);
  EXPECT_EQ(before.instruments[kRight].pose.jaw_angle_rad, 0.5);
  EXPECT_TRUE(before.instruments[kRight].pedal);
  const InputFrame after = replay.Sample(100.0);
  EXPECT_EQ(after.time_s, 100.0);
  EXPECT_EQ(after.instruments[kLeft].pose.yaw_rad, 5.0);
  EXPECT_EQ(after.instruments[kLeft].pose.insertion_m, 0.02);
  EXPECT_EQ(after.instruments[kRight].pose.roll_rad, 3.0);
  EXPECT_TRUE(after.instruments[kRight].pedal);
  EXPECT_EQ(replay.Sample(std::numeric_limits<double>::infinity()).instruments[kLeft].pose.yaw_rad, 5.0);
}

TEST(ReplayInputTest, DurationAndFinished) {
  ReplayInput replay(ThreeFrames());
  EXPECT_EQ(replay.duration_s(), 3.0);
  EXPECT_EQ(replay.start_time_s(), 1.0);
  EXPECT_EQ(replay.end_time_s(), 4.0);
  EXPECT_FALSE(replay.finished(0.0));
  EXPECT_FALSE(replay.finished(4.0));
  EXPECT_TRUE(replay.finished(std::nextafter(4.0, 5.0)));
}

TEST(ReplayInputTest, SamplingOrderDoesNotChangeResults) {
  // The cursor only speeds up forward playback: backwards and jumping give the same values.
  InputRecording rec;
  for (int i = 0; i < 200; ++i) rec.frames.push_back(Frame(0.01 * i, std::sin(i), 0.001 * i, i % 3 == 0, std::cos(i), 0, i % 2 == 0));
  ReplayInput forward(rec);
  ReplayInput jumping(rec);
  for (int k = 0; k <= 2100; ++k) {
    const double t = 0.001 * k - 0.05;
    const double u = 0.001 * ((k * 7919) % 2101) - 0.05;  // a permutation of the same times
    const InputFrame a = forward.Sample(t);
    jumping.Sample(u);
    const InputFrame b = jumping.Sample(t);
    EXPECT_EQ(a.instruments[kLeft].pose.yaw_rad, b.instruments[kLeft].pose.yaw_rad) << t;
    EXPECT_EQ(a.instruments[kRight].pose.roll_rad, b.instruments[kRight].pose.roll_rad) << t;
    EXPECT_EQ(a.instruments[kLeft].pedal, b.instruments[kLeft].pedal) << t;
  }
}

TEST(ReplayInputTest, RejectsBadRecordingsAndNanTime) {
  EXPECT_THROW(ReplayInput(InputRecording{}), std::invalid_argument);
  InputRecording unordered = ThreeFrames();
  std::swap(unordered.frames[0], unordered.frames[1]);
  EXPECT_THROW(ReplayInput(std::move(unordered)), std::invalid_argument);
  ReplayInput replay(ThreeFrames());
  EXPECT_THROW(replay.Sample(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(ReplayInputTest, IsAnInstrumentInputSource) {
  ReplayInput replay(ThreeFrames());
  InstrumentInputSource& source = replay;
  EXPECT_DOUBLE_EQ(source.Sample(2.0).instruments[kLeft].pose.yaw_rad, 4.0);
}

}  // namespace
}  // namespace vesica::device
