#include "app/history/metric_format.h"

#include <gtest/gtest.h>

#include <limits>

namespace vesica::app {
namespace {

TEST(MetricFormatTest, MinutesSeconds) {
  EXPECT_EQ(FormatMinutesSeconds(0), "00:00");
  EXPECT_EQ(FormatMinutesSeconds(59.4), "00:59");
  EXPECT_EQ(FormatMinutesSeconds(59.6), "01:00");
  EXPECT_EQ(FormatMinutesSeconds(754.4), "12:34");
  EXPECT_EQ(FormatMinutesSeconds(4503), "75:03");  // minutes do not wrap into hours
  EXPECT_EQ(FormatMinutesSeconds(-1), "--:--");
  EXPECT_EQ(FormatMinutesSeconds(std::numeric_limits<double>::infinity()), "--:--");
}

TEST(MetricFormatTest, Units) {
  EXPECT_EQ(FormatCentimetres(1.2346), "123.5");
  EXPECT_EQ(FormatCentimetres(0), "0.0");
  EXPECT_EQ(FormatSquareMillimetres(1.25e-5), "12.5");
  EXPECT_EQ(FormatSquareMillimetres(3e-6), "3.0");
  EXPECT_EQ(FormatNewtons(3.14159), "3.14");
  EXPECT_EQ(FormatNewtons(1.2), "1.20");
  EXPECT_EQ(FormatPercent(0.4567), "45.7");
  EXPECT_EQ(FormatPercent(1), "100.0");
  EXPECT_EQ(FormatNewtons(-1e-9), "0.00");  // no "-0.00"
}

TEST(MetricFormatTest, OutcomeWithReason) {
  SessionMetrics m;
  m.gallbladder_free = true;
  m.success = true;
  EXPECT_EQ(FormatOutcome(m), "yes (gallbladder free, no perforation)");
  m.success = false;
  m.perforation = true;
  EXPECT_EQ(FormatOutcome(m), "no (perforated)");
  m.gallbladder_free = false;
  m.perforation = false;
  EXPECT_EQ(FormatOutcome(m), "no (not free)");
  m.perforation = true;
  EXPECT_EQ(FormatOutcome(m), "no (not free, perforated)");
}

}  // namespace
}  // namespace vesica::app

namespace vesica::app {
namespace {

TEST(MetricFormatTest, SpecimenBandsOfTheSeedPaperWithTheirLowerBoundsInside) {
  EXPECT_EQ(FormatSpecimen(0.0), "necrotic debris");
  EXPECT_EQ(FormatSpecimen(0.0049), "necrotic debris");
  EXPECT_EQ(FormatSpecimen(0.005), "good specimen");
  EXPECT_EQ(FormatSpecimen(0.0099), "good specimen");
  EXPECT_EQ(FormatSpecimen(0.010), "some tumour cells");
  EXPECT_EQ(FormatSpecimen(0.0149), "some tumour cells");
  EXPECT_EQ(FormatSpecimen(0.015), "not pathologic");
  EXPECT_EQ(FormatSpecimen(0.2), "not pathologic");
  EXPECT_EQ(FormatSpecimen(-1.0), "-");
  EXPECT_EQ(FormatMillimetres(0.0072), "7.2");
}

TEST(MetricFormatTest, BiopsyOutcomeNamesTheSpecimenOrTheMissingSample) {
  SessionMetrics m;
  EXPECT_EQ(FormatBiopsyOutcome(m), "no (no sample)");
  m.biopsy_sampled = true;
  m.sample_distance_m = 0.003;
  EXPECT_EQ(FormatBiopsyOutcome(m), "no (necrotic debris)");
  m.sample_distance_m = 0.007;
  m.success = true;
  EXPECT_EQ(FormatBiopsyOutcome(m), "yes (good specimen)");
}

}  // namespace
}  // namespace vesica::app
