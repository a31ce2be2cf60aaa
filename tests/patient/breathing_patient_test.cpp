// The whole breathing patient on the synthetic CT (issue 33's acceptance): the tendon's motion and
// breath hold, the fixed crura, ChainMail bounds after every update, the liver following the
// diaphragm and never reaching the lungs, the capsule push, snapshots.
#include "physics/patient/breathing_patient.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "app/patient/synthetic_patient.h"
#include "physics/patient/patient_labels.h"

namespace vesica::physics {
namespace {

const std::shared_ptr<const BreathingPatientModel>& Model() {
  static const std::shared_ptr<const BreathingPatientModel> model =
      BuildBreathingPatientModel(app::patient::GenerateSyntheticPatient().labels);
  return model;
}

TEST(BreathingPatientTest, ModelOfTheSyntheticPatient) {
  const BreathingPatientModel& m = *Model();
  EXPECT_EQ(m.ribs.size(), 24u);
  EXPECT_GT(m.diaphragm.tendon.size(), 20u);
  EXPECT_GT(m.diaphragm.spine_attachment.size(), 3u);
  EXPECT_GT(m.diaphragm.max_tendon_displacement_m, 0.02);  // d_max of the seed fits
  EXPECT_GT(m.liver.coupling.size(), 20u);
  EXPECT_TRUE(m.liver.has_tumour);
}

constexpr double kF = 0.25;                  // the default breathing frequency
constexpr double kPeakIn = 1.0 / (4 * kF);   // sin = 1
constexpr double kPeakOut = 3.0 / (4 * kF);  // sin = -1
constexpr double kDmax = 0.02;

int HighestLiverElement(const BreathingPatientModel& m) {
  const auto& rest = m.liver.lattice.rest_m;
  return static_cast<int>(std::max_element(rest.begin(), rest.end(), [](auto& a, auto& b) { return a.z() < b.z(); }) -
                          rest.begin());
}

TEST(BreathingPatientTest, TendonFollowsEquation12AndStopsInABreathHold) {
  BreathingPatient patient(Model());
  const auto& tendon = Model()->diaphragm.tendon;
  patient.Update(0.0);
  EXPECT_EQ(patient.snapshot().tendon_displacement_m, 0.0);
  for (int e : tendon) EXPECT_EQ(patient.diaphragm_displacement()[e], Eigen::Vector3d::Zero());
  patient.Update(kPeakIn);
  EXPECT_NEAR(patient.snapshot().tendon_displacement_m, kDmax, 1e-12);
  EXPECT_FALSE(patient.snapshot().tendon_limited);
  for (int e : tendon)
    EXPECT_NEAR((patient.diaphragm_displacement()[e] - Eigen::Vector3d(0, 0, -kDmax)).norm(), 0.0, 1e-12);
  patient.Update(kPeakOut);
  EXPECT_NEAR(patient.snapshot().tendon_displacement_m, -kDmax, 1e-12);
  patient.HoldBreath();
  patient.Update(5.0);
  for (double t = 6.0; t < 20.0; t += 0.25) {
    patient.Update(t);
    EXPECT_EQ(patient.snapshot().tendon_displacement_m, 0.0) << t;
    EXPECT_TRUE(patient.snapshot().holding);
    for (int e : tendon) EXPECT_EQ(patient.diaphragm_displacement()[e], Eigen::Vector3d::Zero());
  }
  patient.ResumeBreathing();
  patient.Update(20.0);
  patient.Update(30.0);  // a peak of the phase clock, long after the fade
  EXPECT_NEAR(std::abs(patient.snapshot().tendon_displacement_m), kDmax * std::abs(std::sin(2 * M_PI * kF * 30.0)),
              1e-12);
}

// Ten breaths sampled every 50 ms: every link of both mails within its bounds, the crura still,
// no move refused, the liver below the diaphragm (the lungs' base) everywhere.
TEST(BreathingPatientTest, TenBreathsKeepBoundsCruraAndLungs) {
  const BreathingPatientModel& m = *Model();
  BreathingPatient patient(Model());
  // Liver elements under a diaphragm element with lung over it (within 4 mm sideways, above it at rest).
  std::vector<std::pair<int, int>> under;
  for (int l = 0; l < m.liver.lattice.size(); ++l)
    for (int d = 0; d < m.diaphragm.lattice.size(); ++d) {
      if (!m.diaphragm.pleural[d]) continue;
      const Eigen::Vector3d gap = m.diaphragm.lattice.rest_m[d] - m.liver.lattice.rest_m[l];
      if (gap.head<2>().norm() < 0.004 && gap.z() > 0.0) under.emplace_back(l, d);
    }
  ASSERT_GT(under.size(), 500u);
  double closest_m = INFINITY;
  for (double t = 0.0; t <= 10.0 / kF; t += 0.05) {
    patient.Update(t);
    const PatientSnapshot& s = patient.snapshot();
    ASSERT_EQ(s.blocked, 0) << t;
    ASSERT_LE(m.diaphragm.mail->WorstViolation_m(patient.diaphragm_displacement()), 1e-9) << t;
    ASSERT_LE(m.liver.mail->WorstViolation_m(patient.liver_displacement()), 1e-9) << t;
    for (int e : m.diaphragm.spine_attachment)
      ASSERT_EQ(patient.diaphragm_displacement()[e], Eigen::Vector3d::Zero()) << t;
    for (const auto& [l, d] : under) closest_m = std::min(closest_m, s.diaphragm_m[d].z() - s.liver_m[l].z());
  }
  EXPECT_GT(closest_m, 0.0);
}

TEST(BreathingPatientTest, LiverDomeFollowsTheDiaphragmAndFallsOffBelow) {
  const BreathingPatientModel& m = *Model();
  BreathingPatient patient(Model());
  const int dome = HighestLiverElement(m);
  const auto& rest = m.liver.lattice.rest_m;
  const double top = rest[dome].z();
  const double bottom = std::min_element(rest.begin(), rest.end(), [](auto& a, auto& b) { return a.z() < b.z(); })->z();
  for (double t : {kPeakIn, kPeakOut}) {
    patient.Update(t);
    const double tendon_z = -patient.snapshot().tendon_displacement_m;
    const double dome_z = patient.liver_displacement()[dome].z();
    EXPECT_NEAR(dome_z, tendon_z, 0.2 * std::abs(tendon_z)) << t;
    // Mean cranio-caudal motion in four bands of height: it falls off towards the inferior edge.
    double band_sum[4] = {0, 0, 0, 0};
    int band_count[4] = {0, 0, 0, 0};
    for (int e = 0; e < m.liver.lattice.size(); ++e) {
      const int band = std::min(3, static_cast<int>(4 * (top - rest[e].z()) / (top - bottom)));
      band_sum[band] += std::abs(patient.liver_displacement()[e].z());
      ++band_count[band];
    }
    for (int b = 0; b + 1 < 4; ++b)
      EXPECT_GT(band_sum[b] / band_count[b], band_sum[b + 1] / band_count[b + 1]) << t << " band " << b;
    EXPECT_GT(band_sum[3] / band_count[3], 0.0);  // the inferior edge still moves
    std::printf("t %.1f: tendon %.1f mm, dome %.1f mm, bands %.1f %.1f %.1f %.1f mm, tumour %.1f mm\n", t,
                1e3 * tendon_z, 1e3 * dome_z, 1e3 * band_sum[0] / band_count[0], 1e3 * band_sum[1] / band_count[1],
                1e3 * band_sum[2] / band_count[2], 1e3 * band_sum[3] / band_count[3],
                1e3 * (patient.snapshot().tumour_centre_m - m.liver.tumour_centre_m).z());
  }
}

TEST(BreathingPatientTest, CapsulePushMovesTheThreeNearestAndReleases) {
  const BreathingPatientModel& m = *Model();
  BreathingPatient patient(Model());
  patient.Update(0.7);
  const std::vector<Eigen::Vector3d> free = patient.liver_displacement();
  // A needle from the right flank: its tip 5 mm outside the liver's most lateral capsule element.
  int lateral = m.liver.capsule.front();
  for (int e : m.liver.capsule)
    if (m.liver.lattice.rest_m[e].x() < m.liver.lattice.rest_m[lateral].x()) lateral = e;
  const Eigen::Vector3d tip = patient.snapshot().liver_m[lateral] + Eigen::Vector3d(-0.005, 0, 0);
  const Eigen::Vector3d push(0.006, 0.0, 0.0);
  patient.PushCapsule(tip, push);
  patient.Update(0.7);
  const PatientSnapshot& s = patient.snapshot();
  ASSERT_GE(s.capsule_pushed[2], 0);
  EXPECT_EQ(s.capsule_pushed[0], lateral);
  for (int e : s.capsule_pushed) EXPECT_NEAR((patient.liver_displacement()[e] - free[e] - push).norm(), 0.0, 1e-12);
  EXPECT_LE(m.liver.mail->WorstViolation_m(patient.liver_displacement()), 1e-9);
  int moved = 0;
  for (std::size_t e = 0; e < free.size(); ++e) moved += (patient.liver_displacement()[e] - free[e]).norm() > 1e-12;
  EXPECT_GT(moved, 3);  // 6 mm is beyond the slack: neighbours follow
  patient.ReleaseCapsule();
  patient.Update(0.7);
  for (std::size_t e = 0; e < free.size(); ++e) EXPECT_EQ(patient.liver_displacement()[e], free[e]);
}

TEST(BreathingPatientTest, UpdateDependsOnTimeAloneAndSnapshotsMatch) {
  BreathingPatient patient(Model());
  patient.Update(2.345);
  const PatientSnapshot first = patient.snapshot();
  patient.Update(0.5);
  patient.Update(2.345);
  EXPECT_EQ(patient.snapshot().liver_m, first.liver_m);
  EXPECT_EQ(patient.snapshot().diaphragm_m, first.diaphragm_m);
  patient.Publish();
  const PatientSnapshot& seen = patient.render_snapshots().Latest();
  EXPECT_EQ(seen.time_s, 2.345);
  EXPECT_EQ(seen.liver_m, first.liver_m);
  EXPECT_EQ(patient.haptic_snapshots().Latest().tumour_centre_m, first.tumour_centre_m);
  ASSERT_EQ(seen.ribs.size(), 24u);
}

TEST(BreathingPatientTest, RibsAtPeakTurnByTable1) {
  BreathingPatient patient(Model());
  patient.Update(kPeakIn);
  const auto& ribs = Model()->ribs;
  for (std::size_t r = 0; r < ribs.size(); ++r) {
    const RibAmplitudes table = Table1Amplitudes(ribs[r].number);
    EXPECT_NEAR(patient.snapshot().ribs[r].alpha_rad, table.alpha_max_deg * M_PI / 180, 1e-9);
    EXPECT_NEAR(patient.snapshot().ribs[r].beta_rad, table.beta_max_deg * M_PI / 180, 1e-9);
    const Eigen::Vector3d off_axis = (ribs[r].centre_m - Model()->spine.point_m).cross(Model()->spine.direction);
    EXPECT_LT(off_axis.norm(), 1e-9);
    if (ribs[r].number >= 2) {  // inspiration lifts it
      EXPECT_GT(patient.snapshot().ribs[r].Apply(ribs[r].inertia.centroid_m).z(), ribs[r].inertia.centroid_m.z());
    }
  }
}

TEST(BreathingPatientTest, LabelMapsWithoutAnOrganAreRefused) {
  const auto without = [](std::uint8_t gone, std::uint8_t instead) {
    LabelVolume v = Model()->volume;
    std::replace(v.labels.begin(), v.labels.end(), gone, instead);
    return v;
  };
  const auto message = [](const LabelVolume& v) {
    try {
      (void)BuildBreathingPatientModel(v);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  LabelVolume no_liver = without(patient_label::kLiver, patient_label::kSoftTissue);
  std::replace(no_liver.labels.begin(), no_liver.labels.end(), patient_label::kLiverCapsule,
               patient_label::kSoftTissue);
  std::replace(no_liver.labels.begin(), no_liver.labels.end(), patient_label::kTumour, patient_label::kSoftTissue);
  EXPECT_NE(message(no_liver).find("no liver"), std::string::npos) << message(no_liver);
  const LabelVolume no_spine = without(patient_label::kSpine, patient_label::kSoftTissue);
  EXPECT_NE(message(no_spine).find("no spine"), std::string::npos) << message(no_spine);
  const LabelVolume no_tendon = without(patient_label::kDiaphragmTendon, patient_label::kDiaphragmMuscle);
  EXPECT_NE(message(no_tendon).find("central tendon"), std::string::npos) << message(no_tendon);
}

}  // namespace
}  // namespace vesica::physics
