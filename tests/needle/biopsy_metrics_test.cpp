// Seed 6.3's metrics: precision bands by distance from the tumour's centre and the 'no go' labels.
#include "physics/needle/biopsy_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "physics/patient/patient_labels.h"

namespace vesica::physics {
namespace {
namespace label = patient_label;

TEST(BiopsyMetricsTest, PrecisionBands) {
  EXPECT_EQ(PrecisionOfDistance(0.0), BiopsyPrecision::kNecroticDebris);
  EXPECT_EQ(PrecisionOfDistance(0.003), BiopsyPrecision::kNecroticDebris);
  EXPECT_EQ(PrecisionOfDistance(0.005), BiopsyPrecision::kGoodSpecimen);
  EXPECT_EQ(PrecisionOfDistance(0.007), BiopsyPrecision::kGoodSpecimen);
  EXPECT_EQ(PrecisionOfDistance(0.010), BiopsyPrecision::kSomeTumourCells);
  EXPECT_EQ(PrecisionOfDistance(0.012), BiopsyPrecision::kSomeTumourCells);
  EXPECT_EQ(PrecisionOfDistance(0.015), BiopsyPrecision::kSomeTumourCells);
  EXPECT_EQ(PrecisionOfDistance(0.0151), BiopsyPrecision::kNotPathologic);
  EXPECT_EQ(PrecisionOfDistance(0.020), BiopsyPrecision::kNotPathologic);
  EXPECT_EQ(PrecisionName(BiopsyPrecision::kGoodSpecimen), "good specimen");
  EXPECT_THROW((void)PrecisionOfDistance(-0.001), std::invalid_argument);
  EXPECT_THROW((void)PrecisionOfDistance(NAN), std::invalid_argument);
}

TEST(BiopsyMetricsTest, NoGoLabels) {
  EXPECT_EQ(NoGoOfLabel(label::kLung), NoGo::kLung);
  EXPECT_EQ(NoGoOfLabel(label::kCostophrenicRecess), NoGo::kCostophrenicRecess);
  EXPECT_EQ(NoGoOfLabel(label::kColon), NoGo::kColon);
  EXPECT_EQ(NoGoOfLabel(label::kGallbladder), NoGo::kGallbladder);
  EXPECT_EQ(NoGoOfLabel(label::kSpine), NoGo::kBone);
  EXPECT_EQ(NoGoOfLabel(label::kSternum), NoGo::kBone);
  for (int n = 1; n <= label::kMaxRib; ++n)
    for (bool left : {false, true}) {
      EXPECT_EQ(NoGoOfLabel(label::Rib(left, n)), NoGo::kBone);
      EXPECT_EQ(NoGoOfLabel(label::Bundle(left, n)), NoGo::kNeurovascularBundle);
      EXPECT_FALSE(NoGoOfLabel(label::Cartilage(left, n)).has_value());
    }
  for (std::uint8_t l : {label::kAir, label::kSkin, label::kFat, label::kMuscle, label::kLiver, label::kLiverCapsule,
                         label::kTumour, label::kDiaphragmMuscle, label::kDiaphragmTendon, label::kSoftTissue})
    EXPECT_FALSE(NoGoOfLabel(l).has_value()) << int(l);
}

TEST(BiopsyMetricsTest, TimeAndTotals) {
  BiopsyMetrics m;
  m.start_s = 2.0;
  EXPECT_FALSE(m.time_to_sample_s().has_value());
  m.no_go_crossings[static_cast<std::size_t>(NoGo::kBone)] = 2;
  m.no_go_crossings[static_cast<std::size_t>(NoGo::kLung)] = 1;
  EXPECT_EQ(m.total_no_go_crossings(), 3);
  m.sample = BiopsySample{};
  m.sample->time_s = 47.5;
  EXPECT_DOUBLE_EQ(*m.time_to_sample_s(), 45.5);
}

}  // namespace
}  // namespace vesica::physics
