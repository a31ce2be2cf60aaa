// The breathing signal M(t) = A sin(2 pi f t) (seed eq. 2) and its end-tidal breath hold.
#include "physics/patient/respiration_signal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace vesica::physics {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(RespirationSignalTest, IsTheSeedsSineWhileBreathing) {
  const RespirationSignal signal(RespirationSettings{.frequency_Hz = 0.3});
  EXPECT_EQ(signal.Unit(0.0), 0.0);
  EXPECT_NEAR(signal.Unit(1.0 / (4.0 * 0.3)), 1.0, 1e-15);  // peak inspiration
  EXPECT_NEAR(signal.Unit(3.0 / (4.0 * 0.3)), -1.0, 1e-15);
  for (double t = 0.0; t < 20.0; t += 0.137) EXPECT_NEAR(signal.Unit(t), std::sin(2.0 * kPi * 0.3 * t), 1e-12) << t;
}

TEST(RespirationSignalTest, HoldFadesToEndTidalAndStaysThere) {
  RespirationSignal signal(RespirationSettings{.frequency_Hz = 0.25, .hold_fade_s = 0.8});
  const double t_hold = 1.0;  // at peak inspiration (sin = 1)
  signal.Hold(t_hold);
  EXPECT_TRUE(signal.holding());
  EXPECT_NEAR(signal.Unit(t_hold), 1.0, 1e-12);  // no jump at the request
  for (double t = t_hold + 0.8; t < 30.0; t += 0.05) EXPECT_EQ(signal.Unit(t), 0.0) << t;
}

TEST(RespirationSignalTest, HoldAndResumeAreSmooth) {
  RespirationSignal signal(RespirationSettings{.frequency_Hz = 0.25, .hold_fade_s = 1.0});
  const double h = 1e-4;
  const auto value_and_slope_jump = [&](double t) {
    const double left = signal.Unit(t - h), mid = signal.Unit(t), right = signal.Unit(t + h);
    const double slope_left = (mid - left) / h, slope_right = (right - mid) / h;
    return std::pair{std::abs(right - left), std::abs(slope_right - slope_left)};
  };
  signal.Hold(2.3);
  auto [jump, kink] = value_and_slope_jump(2.3);
  EXPECT_LT(jump, 1e-3);
  EXPECT_LT(kink, 1e-2);
  signal.Resume(7.1);
  std::tie(jump, kink) = value_and_slope_jump(7.1);
  EXPECT_EQ(signal.Unit(7.1), 0.0);
  EXPECT_LT(kink, 1e-2);
  EXPECT_FALSE(signal.holding());
  // Fully resumed after the fade: a sine of amplitude 1 again.
  EXPECT_NEAR(signal.Unit(9.0), std::sin(2.0 * kPi * 0.25 * 9.0), 1e-12);
}

TEST(RespirationSignalTest, FrequencyChangeKeepsThePhase) {
  RespirationSignal signal(RespirationSettings{.frequency_Hz = 0.25});
  const double before = signal.Unit(3.3);
  signal.SetFrequency(3.3, 0.6);  // to hyperventilation
  EXPECT_NEAR(signal.Unit(3.3), before, 1e-12);
  EXPECT_NEAR(signal.Phase_rad(4.3) - signal.Phase_rad(3.3), 2.0 * kPi * 0.6, 1e-12);
}

TEST(RespirationSignalTest, BadSettingsNameTheField) {
  const auto message = [](RespirationSettings s) {
    try {
      ValidateRespirationSettings(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({.frequency_Hz = 0.0}).find("frequency_Hz"), std::string::npos);
  EXPECT_NE(message({.tendon_amplitude_m = -0.01}).find("tendon_amplitude_m"), std::string::npos);
  EXPECT_NE(message({.thoracic_scale = NAN}).find("thoracic_scale"), std::string::npos);
  EXPECT_NE(message({.hold_fade_s = 0.0}).find("hold_fade_s"), std::string::npos);
  EXPECT_EQ(message({}), "");
}

}  // namespace
}  // namespace vesica::physics
