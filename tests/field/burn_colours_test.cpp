// The cautery colour ramp (issue 30): a fresh burn whitens first (coagulation), then browns and
// blackens with dose, and a full burn is an obvious change of colour (CIE Delta E >= 20) on
// every organ the hook can touch.

#include "app/render/burn_colours.h"

#include <gtest/gtest.h>

#include "app/render/render_colours.h"
#include "cie_lab.h"

namespace vesica::app {
namespace {

using testing::DeltaE76;
using testing::Lab;
using testing::SrgbToLab;

Lab LabOf(const std::array<std::uint8_t, 3>& c) { return SrgbToLab(c[0], c[1], c[2]); }

TEST(BurnColours, UnburntIsTheShadedTissueColour) {
  const auto c = BurnedColour(kLiverRgb, 0.8, 0.0f);
  EXPECT_EQ(c[0], static_cast<std::uint8_t>(std::lround(255 * 0.8 * kLiverRgb[0])));
  EXPECT_EQ(c[1], static_cast<std::uint8_t>(std::lround(255 * 0.8 * kLiverRgb[1])));
  EXPECT_EQ(c[2], static_cast<std::uint8_t>(std::lround(255 * 0.8 * kLiverRgb[2])));
}

TEST(BurnColours, AFreshBurnWhitensBeforeItDarkens) {
  for (const double* tissue : {kLiverRgb, kGallbladderRgb, kMembraneRgb}) {
    const double tissue_L = LabOf(BurnedColour(tissue, 1.0, 0.0f)).L;
    const double coagulated_L = LabOf(BurnedColour(tissue, 1.0, static_cast<float>(kCoagulatedLevel))).L;
    // Coagulation is paler than the liver and the gallbladder (the membrane is already pale).
    if (tissue != kMembraneRgb) {
      EXPECT_GT(coagulated_L, tissue_L + 20);
    }
    // Past coagulation the lightness only falls: browning, then char.
    double previous = coagulated_L;
    for (float level = static_cast<float>(kCoagulatedLevel) + 0.05f; level <= 1.0f; level += 0.05f) {
      const double L = LabOf(BurnedColour(tissue, 1.0, level)).L;
      EXPECT_LE(L, previous + 1e-9) << "level " << level;
      previous = L;
    }
  }
}

TEST(BurnColours, AFullBurnIsAnObviousChangeOnEveryTissue) {
  for (const double* tissue : {kLiverRgb, kGallbladderRgb, kMembraneRgb})
    for (double shade : {0.6, 1.0}) {
      const Lab before = LabOf(BurnedColour(tissue, shade, 0.0f));
      const Lab charred = LabOf(BurnedColour(tissue, shade, 1.0f));
      EXPECT_GE(DeltaE76(before, charred), 20.0);
      EXPECT_LT(charred.L, before.L);
    }
}

TEST(BurnColours, LevelsOutsideTheUnitIntervalClamp) {
  EXPECT_EQ(BurnedColour(kLiverRgb, 1.0, -3.0f), BurnedColour(kLiverRgb, 1.0, 0.0f));
  EXPECT_EQ(BurnedColour(kLiverRgb, 1.0, 7.0f), BurnedColour(kLiverRgb, 1.0, 1.0f));
}

}  // namespace
}  // namespace vesica::app
