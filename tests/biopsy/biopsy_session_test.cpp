// The needle-biopsy session (app/biopsy): the stylus' placement, the committed recorded biopsy
// replayed to its metrics, determinism, and bad input.

#include "app/biopsy/biopsy_session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <fstream>
#include <sstream>

#include "app/biopsy/biopsy_replay.h"
#include "app/biopsy/scripted_biopsy.h"
#include "device/stylus/stylus_recording.h"

namespace vesica::app::biopsy {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = VESICA_DATA_DIR;

std::shared_ptr<const BiopsyPatient> Patient() {
  static const auto patient = LoadCommittedBiopsyPatient(kData / "patients");
  return patient;
}

TEST(StylusPlacementTest, DeviceAxesAreTheTraineesAtThePatientsRightAndRoundTrip) {
  const StylusPlacement placement = PlacementAtRightSide(Eigen::Vector3d(-0.075, 0.02, -0.045));
  EXPECT_NEAR(placement.R_WB.determinant(), 1.0, 1e-15);
  EXPECT_TRUE((placement.R_WB.transpose() * placement.R_WB).isIdentity(1e-15));
  // The stylus pointing down (-y of the device) points posterior into the supine patient.
  device::StylusState down;
  down.p_BTip_B = Eigen::Vector3d(0.01, -0.02, 0.03);
  down.d_B = -Eigen::Vector3d::UnitY();
  const physics::NeedlePose pose = NeedleInWorld(placement, down);
  EXPECT_TRUE(pose.direction.isApprox(-Eigen::Vector3d::UnitY()));
  // 1.5 x: device x (trainee's right) is cranial, z (toward the trainee) the patient's right.
  EXPECT_TRUE(pose.tip_m.isApprox(Eigen::Vector3d(-0.075 - 1.5 * 0.03, 0.08 - 1.5 * 0.02, -0.045 + 1.5 * 0.01)));
  const device::StylusState back = StylusForNeedle(placement, pose);
  EXPECT_TRUE(back.p_BTip_B.isApprox(down.p_BTip_B, 1e-14));
  EXPECT_TRUE(back.d_B.isApprox(down.d_B, 1e-14));
  EXPECT_TRUE(ForceOnDevice(placement, Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));
}

TEST(ScriptedBiopsyTest, CommittedRecordingIsTheScriptForTheCommittedPatient) {
  const auto patient = Patient();
  const auto script = ScriptBiopsy(PlacementAtRightSide(patient->model->liver.tumour_centre_m));
  std::ifstream in(kData / "recordings" / "biopsy.csv", std::ios::binary);
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_EQ(committed.str(), device::FormatStylusRecording(script))
      << "regenerate with: build/release/app/biopsy/vesica-script-biopsy";
}

TEST(BiopsyReplayTest, CommittedBiopsyTakesAGoodSpecimenAtEndExpirationWithoutHarm) {
  const auto recording = device::ReadStylusRecording(kData / "recordings" / "biopsy.csv");
  const BiopsyReplayResult r = ReplayBiopsy(Patient(), recording);
  EXPECT_EQ(r.ticks, 12001);
  ASSERT_TRUE(r.metrics.biopsy_sampled);
  EXPECT_DOUBLE_EQ(r.metrics.time_to_sample_s, 8.0);
  // 7 mm short of the tumour's centre at end tidal (where the CT shows it), give or take the
  // capsule's push and what breathing left: within the good-specimen band.
  EXPECT_GT(r.metrics.sample_distance_m, 0.005);
  EXPECT_LT(r.metrics.sample_distance_m, 0.010);
  EXPECT_EQ(r.needle_metrics.sample->precision, physics::BiopsyPrecision::kGoodSpecimen);
  EXPECT_EQ(r.metrics.insertion_attempts, 1);
  EXPECT_EQ(r.metrics.nogo_crossings, 0);
  EXPECT_TRUE(r.metrics.success);
  EXPECT_DOUBLE_EQ(r.metrics.duration_s, 8.0);
  EXPECT_GT(r.metrics.max_force_N, 0.0);
  EXPECT_LE(r.metrics.max_force_N, physics::NeedleHapticsParameters{}.max_force_N + 1e-12);
  // The same recording, the same numbers, bit for bit.
  const BiopsyReplayResult again = ReplayBiopsy(Patient(), recording);
  EXPECT_EQ(again.metrics.sample_distance_m, r.metrics.sample_distance_m);
  EXPECT_EQ(again.metrics.max_force_N, r.metrics.max_force_N);
  EXPECT_EQ(again.metrics.mean_force_N, r.metrics.mean_force_N);
}

TEST(BiopsySessionTest, NoSampleIsNoSuccessAndTheDurationRuns) {
  BiopsySession session(Patient());
  device::StylusState outside;  // the workspace centre: 6 cm anterior of the tumour, outside the body
  outside.p_BTip_B = Eigen::Vector3d(0, 0.09, 0);
  for (int k = 0; k <= 500; ++k) session.Tick(outside, k * 0.001);
  const SessionMetrics m = session.Metrics();
  EXPECT_FALSE(m.biopsy_sampled);
  EXPECT_FALSE(m.success);
  EXPECT_DOUBLE_EQ(m.duration_s, 0.5);
  EXPECT_EQ(m.insertion_attempts, 0);
  EXPECT_EQ(session.DeviceForce(), Eigen::Vector3d::Zero());
}

TEST(BiopsySessionTest, BadSamplesAndTimesAreRefusedWithTheStateUnchanged) {
  BiopsySession session(Patient());
  device::StylusState good;
  good.p_BTip_B = Eigen::Vector3d(0, 0.05, 0);
  session.Tick(good, 0.010);
  const physics::NeedlePose before = session.needle_pose();
  device::StylusState nan = good;
  nan.p_BTip_B.x() = std::nan("");
  EXPECT_THAT([&] { session.Tick(nan, 0.011); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("stylus")));
  device::StylusState zero = good;
  zero.d_B = Eigen::Vector3d::Zero();
  EXPECT_THAT([&] { session.Tick(zero, 0.011); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("zero length")));
  EXPECT_THAT([&] { session.Tick(good, 0.005); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("before")));
  EXPECT_EQ(session.time_s(), 0.010);
  EXPECT_EQ(session.needle_pose().tip_m, before.tip_m);
  BiopsySessionSettings bad;
  bad.patient_period_s = 0;
  EXPECT_THAT([&] { BiopsySession s(Patient(), bad); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("patient_period_s")));
}

}  // namespace
}  // namespace vesica::app::biopsy
