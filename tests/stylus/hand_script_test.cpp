#include "app/omnisim/hand_script.h"

#include <gtest/gtest.h>

#include <cmath>

#include "device/stylus/stylus_capabilities.h"

namespace vesica::app {
namespace {

TEST(HandScriptTest, BuiltInBiopsyPhases) {
  const BuiltInBiopsyMotion motion;
  const HandScript script(BuiltInBiopsyRecording(motion));
  EXPECT_NEAR(script.period_s(), 6.5, 1e-12);
  const Eigen::Vector3d d = script.At(0.0).d_B;
  EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  EXPECT_NEAR(std::acos(-d.y()), motion.tilt_rad, 1e-12);  // 30 degrees from vertical
  // Approach: starts 40 mm before the entry on the line, reaches the entry at 1 s.
  EXPECT_LT((script.At(0.0).p_BTip_B - (motion.entry_m - motion.approach_m * d)).norm(), 1e-12);
  EXPECT_LT((script.At(1.0).p_BTip_B - motion.entry_m).norm(), 1e-12);
  // Insert: 50 mm along D at 3 s, held to 4 s, with the biopsy click in the middle.
  const Eigen::Vector3d deepest = motion.entry_m + motion.insertion_m * d;
  EXPECT_LT((script.At(3.0).p_BTip_B - deepest).norm(), 1e-12);
  EXPECT_LT((script.At(3.9).p_BTip_B - deepest).norm(), 1e-12);
  EXPECT_EQ(script.At(3.5).buttons, device::kStylusButton1);
  EXPECT_EQ(script.At(3.0).buttons, 0u);
  EXPECT_EQ(script.At(3.7).buttons, 0u);
  // Every point of the motion stays on the insertion line and inside the Omni's workspace.
  const device::StylusCapabilities caps = device::PhantomOmniCapabilities();
  for (double t = 0.0; t < 6.5; t += 0.013) {
    const Eigen::Vector3d p = script.At(t).p_BTip_B - motion.entry_m;
    EXPECT_LT((p - p.dot(d) * d).norm(), 1e-12) << t;
    EXPECT_TRUE(device::InsideWorkspace(caps, script.At(t).p_BTip_B)) << t;
  }
  // It repeats.
  EXPECT_LT((script.At(6.5 + 3.0).p_BTip_B - deepest).norm(), 1e-9);
}

}  // namespace
}  // namespace vesica::app
