// The node's hand sensors with image layout 2's calibration applied (hand_calibration.h): roll less
// the sensor offset (wrapped), the jaw normalised to its measured span (either counting
// direction), the pedal pressed past half its measured travel; not measured, the board's values.
#include "firmware_protocol/node/hand_calibration.h"

#include <gtest/gtest.h>

namespace vesica::fp {
namespace {

HardwareSample Sample(float roll_rad, std::int32_t jaw_raw, std::int32_t pedal_raw) {
  HardwareSample s;
  s.roll_rad = roll_rad;
  s.jaw_rad = 0.123f;  // the board's own conversion
  s.pedal = true;
  s.jaw_raw = jaw_raw;
  s.pedal_raw = pedal_raw;
  return s;
}

TEST(HandCalibrationTest, NotMeasuredTheBoardsValuesStand) {
  const ParameterStore defaults;  // a layout-1 image migrates to these
  const HandReading h = calibrated_hand(defaults, Sample(0.5f, 2000, 100));
  EXPECT_FLOAT_EQ(h.roll_rad, 0.5f);
  EXPECT_FLOAT_EQ(h.jaw_rad, 0.123f);
  EXPECT_TRUE(h.pedal);
}

TEST(HandCalibrationTest, MeasuredSpansNormaliseJawAndPedalAndTheRollOffsetIsTakenOff) {
  ParameterStore p;
  ASSERT_TRUE(p.set_internal_f32(param::kRollSensorOffset, 3.0f));
  ASSERT_TRUE(p.set_internal(param::kJawClosedCounts, 3600));  // this sensor counts down as it opens
  ASSERT_TRUE(p.set_internal(param::kJawOpenCounts, 1200));
  ASSERT_TRUE(p.set_internal(param::kPedalReleasedCounts, 400));
  ASSERT_TRUE(p.set_internal(param::kPedalPressedCounts, 3200));
  // Roll: -3.0 rad read with a +3.0 rad offset is -6.0, i.e. 0.2832 rad once wrapped.
  EXPECT_NEAR(calibrated_hand(p, Sample(-3.0f, 3600, 400)).roll_rad, -6.0f + 2.0f * 3.14159265f, 1e-5f);
  EXPECT_NEAR(calibrated_hand(p, Sample(3.1f, 3600, 400)).roll_rad, 0.1f, 1e-5f);
  // Jaw: closed 0, a quarter of the span 0.15 rad, open 0.6 rad (jaw_open_rad's default), beyond
  // either end clamped.
  EXPECT_FLOAT_EQ(calibrated_hand(p, Sample(0, 3600, 400)).jaw_rad, 0.0f);
  EXPECT_NEAR(calibrated_hand(p, Sample(0, 3000, 400)).jaw_rad, 0.15f, 1e-6f);
  EXPECT_NEAR(calibrated_hand(p, Sample(0, 1200, 400)).jaw_rad, 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(calibrated_hand(p, Sample(0, 4000, 400)).jaw_rad, 0.0f);
  EXPECT_NEAR(calibrated_hand(p, Sample(0, 100, 400)).jaw_rad, 0.6f, 1e-6f);
  // Pedal: half its travel is 1800 counts.
  EXPECT_FALSE(calibrated_hand(p, Sample(0, 3600, 400)).pedal);
  EXPECT_FALSE(calibrated_hand(p, Sample(0, 3600, 1790)).pedal);
  EXPECT_TRUE(calibrated_hand(p, Sample(0, 3600, 1810)).pedal);
  EXPECT_TRUE(calibrated_hand(p, Sample(0, 3600, 3200)).pedal);
}

}  // namespace
}  // namespace vesica::fp
