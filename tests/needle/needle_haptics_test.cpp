// The needle on the synthetic breathing patient (issue 34's acceptance, physics part): a scripted
// insertion's force profile (a step at each tissue plane, eq. 14 at the capsule), the lateral
// constraint, biopsy bands, no-go crossings, attempts, continuity while breathing, bad input.
#include "physics/needle/needle_haptics.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "needle_test_patient.h"
#include "physics/patient/breathing_patient.h"
#include "physics/patient/patient_labels.h"

namespace vesica::physics {
namespace {
using needle_test::Patient;
namespace label = patient_label;

constexpr double kNPerHu = 7e-4;  // the documented default axial_N_per_HU

// The documented eq. 14 parameters (docs/needle.md), written out here, not taken from the code.
double Eq14(double tau, double omega, double nu, double phi, double d) {
  return (nu + phi) * std::exp(tau * (d - omega)) + phi;
}
double DocumentedBefore(double d) {
  const double a = 2.0 / (1.0 - std::exp(-3.0));
  return Eq14(300.0, 0.010, a - (2.0 - a), 2.0 - a, d);
}
double DocumentedAfter(double d) { return Eq14(30.0, 0.010, 0.2, 0.2, d); }

// The label map's own label and HU at the voxel nearest p (independent of DeformedCt).
std::uint8_t RestLabel(const Eigen::Vector3d& p) {
  const LabelVolume& v = Patient().volume.labels;
  const Eigen::Vector3d idx = (v.direction * v.spacing_m.asDiagonal()).inverse() * (p - v.origin_m);
  return v.At(static_cast<int>(std::lround(idx.x())), static_cast<int>(std::lround(idx.y())),
              static_cast<int>(std::lround(idx.z())));
}

struct Tick {
  double s_m;  // distance from the scripted start
  NeedleForces f;
  std::uint8_t label;
};

// Moves the needle's tip from start along `motion` in steps of step_m up to length_m, one tick
// each, the needle pointing along `pointing` (by default the way it moves: an insertion).
std::vector<Tick> Insert(NeedleHaptics& needle, const Eigen::Vector3d& start, const Eigen::Vector3d& motion,
                         double length_m, double& t, double step_m = 0.0001,
                         const Eigen::Vector3d& pointing = Eigen::Vector3d::Zero()) {
  const Eigen::Vector3d direction = pointing.isZero() ? motion : pointing;
  std::vector<Tick> ticks;
  const int n = static_cast<int>(std::lround(length_m / step_m));
  for (int k = 0; k <= n; ++k) {
    const Eigen::Vector3d tip = start + (k * step_m) * motion;
    t += 0.001;
    ticks.push_back({k * step_m, needle.Update({tip, direction}, t), RestLabel(tip)});
  }
  return ticks;
}
// Draws the needle back (pointing along -motion).
std::vector<Tick> Withdraw(NeedleHaptics& needle, const Eigen::Vector3d& start, const Eigen::Vector3d& pointing,
                           double length_m, double& t, double step_m) {
  return Insert(needle, start, -pointing, length_m, t, step_m, pointing);
}

// The first distance along the ticks where the rest label becomes l.
double FirstAt(const std::vector<Tick>& ticks, std::uint8_t l) {
  for (const Tick& tick : ticks)
    if (tick.label == l) return tick.s_m;
  return NAN;
}
const Tick& At(const std::vector<Tick>& ticks, double s) {
  const auto it = std::lower_bound(ticks.begin(), ticks.end(), s - 1e-9,
                                   [](const Tick& tick, double value) { return tick.s_m < value; });
  return *it;
}

TEST(NeedleHapticsTest, ScriptedInsertionStepsAtEachPlanePeaksAtTheCapsuleAndDrops) {
  NeedleHaptics needle(Patient().ct);
  double t = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  const double to_tumour = (needle_test::TumourCentre() - needle_test::kAnteriorStart).norm();
  const std::vector<Tick> ticks = Insert(needle, needle_test::kAnteriorStart, D, to_tumour, t);

  const double skin = FirstAt(ticks, label::kSkin), fat = FirstAt(ticks, label::kFat),
               muscle = FirstAt(ticks, label::kMuscle), capsule = FirstAt(ticks, label::kLiverCapsule),
               tumour = FirstAt(ticks, label::kTumour);
  ASSERT_TRUE(skin < fat && fat < muscle && muscle < capsule && capsule < tumour) << skin << fat << muscle << capsule;
  EXPECT_EQ(needle.metrics().insertion_attempts, 1);
  EXPECT_EQ(needle.metrics().total_no_go_crossings(), 0);

  // Outside the body: nothing at all.
  for (const Tick& tick : ticks)
    if (tick.s_m < skin - 0.0021) {  // the skin voxel's trilinear reach starts a voxel out
      EXPECT_FALSE(tick.f.inside);
      EXPECT_EQ(tick.f.total_N, Eigen::Vector3d::Zero());
    }
  // Inside a layer (a voxel away from its planes) the axial force is flat; across a plane it steps
  // by k |HU_a - HU_b| (the synthetic patient's HU: fat -100, muscle 45, liver 60, tumour 30).
  const auto axial = [&](double s) { return -At(ticks, s).f.axial_N.dot(D); };
  const double h = 0.002;  // one voxel
  EXPECT_NEAR(axial(fat + h), axial(muscle - h), 1e-12);
  EXPECT_NEAR(axial(muscle + h), axial(capsule - h), 1e-12);
  EXPECT_NEAR(axial(muscle + h) - axial(muscle - h), kNPerHu * 145.0, 1e-9);
  // Skin: up from air (-1000 to 30) and down to fat (-100): 1160 HU over one 2 mm voxel; sampled
  // every 1 mm the thin layer's peak may fall between samples.
  EXPECT_NEAR(axial(fat + h), kNPerHu * 1160.0, kNPerHu * 1160.0 * 0.15);
  // Muscle, capsule, liver (felt once the capsule is perforated): 45 -> 75 -> 60, a thin layer
  // like the skin.
  EXPECT_NEAR(axial(tumour - 2 * h) - axial(capsule - h), kNPerHu * 45.0, kNPerHu * 45.0 * 0.15);
  RecordProperty("capsule_plane_HU", std::to_string((axial(tumour - 2 * h) - axial(capsule - h)) / kNPerHu));
  RecordProperty("skin_plane_HU", std::to_string(axial(fat + h) / kNPerHu));
  // Liver into tumour (after puncture): 60 -> 30.
  EXPECT_NEAR(axial(tumour + h) - axial(tumour - 2 * h), kNPerHu * 30.0, 1e-9);

  // The capsule: touched, pushed (eq. 14 before), punctured (eq. 14 after).
  const Tick* touch = nullptr;
  const Tick* last_push = nullptr;
  const Tick* first_after = nullptr;
  for (const Tick& tick : ticks) {
    if (tick.f.capsule == CapsuleContact::kPushing) {
      if (!touch) touch = &tick;
      last_push = &tick;
    }
    if (tick.f.capsule == CapsuleContact::kPunctured && !first_after) first_after = &tick;
  }
  ASSERT_TRUE(touch && last_push && first_after);
  EXPECT_NEAR(touch->s_m, capsule, 0.0021);  // touched within a voxel of the capsule's first voxel
  const Eigen::Vector3d contact = touch->f.capsule_contact_m;
  EXPECT_EQ(RestLabel(contact), label::kLiverCapsule);
  int eq14_checked = 0;
  for (const Tick& tick : ticks) {
    if (tick.f.capsule == CapsuleContact::kNone) continue;
    EXPECT_NEAR((tick.f.capsule_contact_m - contact).norm(), 0.0, 1e-12);  // still patient: the contact stays
    const double d = (needle_test::kAnteriorStart + tick.s_m * D - contact).dot(D);
    const double expected = tick.f.capsule == CapsuleContact::kPushing ? DocumentedBefore(d) : DocumentedAfter(d);
    EXPECT_NEAR(tick.f.capsule_force_N, expected, 1e-9) << tick.s_m;
    EXPECT_NEAR(-tick.f.capsule_N.dot(D), expected, 1e-9);
    ++eq14_checked;
  }
  EXPECT_GT(eq14_checked, 300);
  // The peak just before puncture, the drop after it (total force along the needle).
  EXPECT_NEAR(last_push->f.capsule_force_N, 2.0, 0.01);
  EXPECT_GT(last_push->f.capsule_force_N, 1.9);
  double peak_total = 0.0;
  for (const Tick& tick : ticks)
    if (tick.s_m <= last_push->s_m) peak_total = std::max(peak_total, -tick.f.total_N.dot(D));
  EXPECT_NEAR(-last_push->f.total_N.dot(D), peak_total, 1e-12);               // the largest force before puncture
  EXPECT_LT(-first_after->f.total_N.dot(D), peak_total - 1.0);                // sharp drop
  EXPECT_GT(-ticks.back().f.total_N.dot(D), -first_after->f.total_N.dot(D));  // rising resistance after
  EXPECT_FALSE(last_push->f.clamped);
}

TEST(NeedleHapticsTest, CapsuleIsPushedVisiblyBeforePuncture) {
  BreathingPatient patient(Patient().model);
  NeedleHaptics needle(Patient().ct);
  double t = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  std::vector<Tick> ticks = Insert(needle, needle_test::kAnteriorStart, D, 0.07, t, 0.0005);
  ASSERT_EQ(needle.forces().capsule, CapsuleContact::kPushing);
  const CapsulePush push = needle.capsule_push();
  ASSERT_TRUE(push.active);
  EXPECT_GT(push.displacement_m.norm(), 0.001);
  patient.PushCapsule(push.surface_m, push.displacement_m);
  patient.Update(0.0);
  const std::vector<Eigen::Vector3d> points = PushedCapsulePoints(patient.snapshot());
  ASSERT_EQ(points.size(), 3u);
  for (int n = 0; n < 3; ++n) {
    const auto e = static_cast<std::size_t>(patient.snapshot().capsule_pushed[n]);
    EXPECT_NEAR((points[n] - patient.snapshot().liver_breathing_m[e] - push.displacement_m).norm(), 0.0, 1e-9);
    EXPECT_LT((patient.snapshot().liver_breathing_m[e] - push.surface_m).norm(), 0.015);  // near the contact
  }
  // The haptics map the CT through the liver before the push: the contact does not run ahead.
  needle.SetPatient(patient.snapshot(), t);
  t += 1.0;
  const NeedleForces& f = needle.Update({needle_test::kAnteriorStart + 0.07 * D, D}, t);
  EXPECT_NEAR((f.capsule_contact_m - push.surface_m).norm(), 0.0, 1e-9);
  // Puncture releases the capsule.
  Insert(needle, needle_test::kAnteriorStart + 0.07 * D, D, 0.012, t, 0.0005);
  EXPECT_EQ(needle.forces().capsule, CapsuleContact::kPunctured);
  EXPECT_FALSE(needle.capsule_push().active);
}

TEST(NeedleHapticsTest, WithdrawalIsContinuous) {
  // Out from the tumour to outside the body in 0.05 mm steps: every plane is a ramp over a voxel,
  // the liver lets go of the needle without a jump (the puncture's drop is felt going in only).
  NeedleHaptics needle(Patient().ct);
  double t = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  const double length = (needle_test::TumourCentre() - needle_test::kAnteriorStart).norm();
  Insert(needle, needle_test::kAnteriorStart, D, length, t, 0.0005);
  ASSERT_EQ(needle.forces().capsule, CapsuleContact::kPunctured);
  const std::vector<Tick> out = Withdraw(needle, needle_test::kAnteriorStart + length * D, D, length, t, 0.00005);
  double largest = 0.0;
  for (std::size_t k = 1; k < out.size(); ++k)
    largest = std::max(largest, (out[k].f.total_N - out[k - 1].f.total_N).norm());
  EXPECT_FALSE(out.back().f.inside);
  EXPECT_LT(largest, 0.05);
}

TEST(NeedleHapticsTest, LateralForceGrowsWithDeviationOnceInsertedAndIsZeroOutside) {
  NeedleHaptics needle(Patient().ct);
  double t = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  Insert(needle, needle_test::kAnteriorStart, D, 0.05, t);  // 15 mm in (skin at 34 mm)
  const Eigen::Vector3d on_line = needle_test::kAnteriorStart + 0.05 * D;
  t += 0.001;
  EXPECT_EQ(needle.Update({on_line, D}, t).lateral_N, Eigen::Vector3d::Zero());
  EXPECT_GT(needle.forces().inserted_m, 0.01);
  double previous = 0.0;
  for (double delta : {0.0005, 0.001, 0.002, 0.004}) {
    t += 0.001;
    const NeedleForces& f = needle.Update({on_line + Eigen::Vector3d(delta, 0, 0), D}, t);
    EXPECT_NEAR(f.deviation_m, delta, 1e-12);
    EXPECT_NEAR(f.lateral_N.x(), -300.0 * delta, 1e-9);  // k_lat e, back to the line
    EXPECT_NEAR(f.lateral_N.y(), 0.0, 1e-12);
    EXPECT_GT(f.lateral_N.norm(), previous);
    previous = f.lateral_N.norm();
  }
  // Just past the skin the constraint is only growing in.
  NeedleHaptics shallow(Patient().ct);
  double t2 = 0.0;
  const std::vector<Tick> ticks = Insert(shallow, needle_test::kAnteriorStart, D, 0.0355, t2);
  ASSERT_TRUE(shallow.forces().inside);
  ASSERT_LT(shallow.forces().inserted_m, 0.005);
  t2 += 0.001;
  const NeedleForces& f =
      shallow.Update({needle_test::kAnteriorStart + 0.0355 * D + Eigen::Vector3d(0.004, 0, 0), D}, t2);
  EXPECT_LT(f.lateral_N.norm(), 300.0 * 0.004);
  // Outside, the same deviation gives nothing.
  t += 0.001;
  const NeedleForces& outside = needle.Update({needle_test::kAnteriorStart + Eigen::Vector3d(0.004, 0, 0), D}, t);
  EXPECT_FALSE(outside.inside);
  EXPECT_EQ(outside.lateral_N, Eigen::Vector3d::Zero());
  EXPECT_EQ(outside.total_N, Eigen::Vector3d::Zero());
}

TEST(NeedleHapticsTest, ForceIsBoundedByTheDevice) {
  NeedleHapticsParameters p;
  p.max_force_N = 1.0;
  NeedleHaptics needle(Patient().ct, p);
  double t = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  const std::vector<Tick> ticks = Insert(needle, needle_test::kAnteriorStart, D, 0.075, t);
  bool clamped = false;
  for (const Tick& tick : ticks) {
    EXPECT_LE(tick.f.total_N.norm(), 1.0 + 1e-12);
    if (tick.f.clamped) {
      clamped = true;
      const Eigen::Vector3d sum = tick.f.axial_N + tick.f.lateral_N + tick.f.capsule_N + tick.f.grip_N;
      EXPECT_NEAR((tick.f.total_N - sum.normalized()).norm(), 0.0, 1e-12);  // same direction, at the bound
    }
  }
  EXPECT_TRUE(clamped);
}

TEST(NeedleHapticsTest, BiopsiesLandInTheFourBands) {
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  const Eigen::Vector3d centre = needle_test::TumourCentre();
  const struct {
    double distance_m;
    BiopsyPrecision band;
  } cases[] = {{0.003, BiopsyPrecision::kNecroticDebris},
               {0.007, BiopsyPrecision::kGoodSpecimen},
               {0.012, BiopsyPrecision::kSomeTumourCells},
               {0.020, BiopsyPrecision::kNotPathologic}};
  for (const auto& c : cases) {
    NeedleHaptics needle(Patient().ct, {}, 1.5);
    double t = 1.5;
    // Short of the centre along the path by the distance.
    const double length = (centre - needle_test::kAnteriorStart).norm() - c.distance_m;
    Insert(needle, needle_test::kAnteriorStart, D, length, t, 0.0005);
    const BiopsySample s = needle.TakeBiopsy(t);
    EXPECT_TRUE(s.inside_body);
    EXPECT_NEAR(s.distance_m, c.distance_m, 1e-9);
    EXPECT_EQ(s.precision, c.band) << c.distance_m;
    ASSERT_TRUE(needle.metrics().sample.has_value());
    EXPECT_NEAR(*needle.metrics().time_to_sample_s(), t - 1.5, 1e-12);
    // A second press is reported, the first sample stays the task's.
    t += 0.5;
    needle.TakeBiopsy(t);
    EXPECT_NEAR(needle.metrics().sample->time_s, t - 0.5, 1e-12);
  }
}

TEST(NeedleHapticsTest, RibAndLungPathsEachCountANoGoCrossing) {
  const Eigen::Vector3d to_tumour = (needle_test::TumourCentre() - needle_test::kRibStart).normalized();
  {
    NeedleHaptics needle(Patient().ct);
    double t = 0.0;
    Insert(needle, needle_test::kRibStart, to_tumour, 0.09, t, 0.0005);
    EXPECT_EQ(needle.metrics().crossings(NoGo::kBone), 1);
    EXPECT_EQ(needle.metrics().total_no_go_crossings(), 1);
  }
  {
    NeedleHaptics needle(Patient().ct);
    double t = 0.0;
    Insert(needle, needle_test::kLungStart, Eigen::Vector3d::UnitX(), 0.09, t, 0.0005);
    EXPECT_EQ(needle.metrics().crossings(NoGo::kLung), 1);
    EXPECT_EQ(needle.metrics().total_no_go_crossings(), 1);
  }
}

TEST(NeedleHapticsTest, WithdrawalAndReentryIsASecondAttempt) {
  NeedleHaptics needle(Patient().ct);
  double t = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  Insert(needle, needle_test::kAnteriorStart, D, 0.05, t, 0.0005);
  EXPECT_EQ(needle.metrics().insertion_attempts, 1);
  // Back a little, still inside, and on again: the same attempt.
  Withdraw(needle, needle_test::kAnteriorStart + 0.05 * D, D, 0.008, t, 0.0005);
  Insert(needle, needle_test::kAnteriorStart + 0.042 * D, D, 0.008, t, 0.0005);
  EXPECT_EQ(needle.metrics().insertion_attempts, 1);
  // Out of the skin, then in again at a new angle.
  Withdraw(needle, needle_test::kAnteriorStart + 0.05 * D, D, 0.05, t, 0.0005);
  EXPECT_FALSE(needle.forces().inside);
  EXPECT_EQ(needle.forces().total_N, Eigen::Vector3d::Zero());
  const Eigen::Vector3d tilted = Eigen::Vector3d(0.1, -1.0, 0.0).normalized();
  Insert(needle, needle_test::kAnteriorStart, tilted, 0.05, t, 0.0005);
  EXPECT_EQ(needle.metrics().insertion_attempts, 2);
  EXPECT_NEAR(needle.forces().deviation_m, 0.0, 1e-12);  // the new line is the new insertion's
}

TEST(NeedleHapticsTest, BreathingUnderTheNeedleIsFeltAndContinuousAcrossUpdates) {
  BreathingPatient patient(Patient().model);
  NeedleHapticsParameters p;
  p.blend_s = 0.02;  // the physics publishes every 20 ms
  NeedleHaptics needle(Patient().ct, p);
  double t = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  // Into the tumour with the patient still (t = 0 is end tidal), then held there while it breathes.
  const double length = (needle_test::TumourCentre() - needle_test::kAnteriorStart).norm();
  Insert(needle, needle_test::kAnteriorStart, D, length, t, 0.0005);
  ASSERT_EQ(needle.forces().capsule, CapsuleContact::kPunctured);
  const NeedlePose held{needle_test::kAnteriorStart + length * D, D};
  std::vector<Eigen::Vector3d> force;
  std::vector<double> update_jump;  // the force's change over a whole physics period
  double patient_t = 0.0;
  for (int tick = 1; tick <= 4000; ++tick) {  // one breath at 0.25 Hz, 1 kHz
    const double now = t + tick * 0.001;
    if (tick % 20 == 0) {
      patient_t = tick * 0.001;
      patient.Update(patient_t);
      needle.SetPatient(patient.snapshot(), now);
    }
    force.push_back(needle.Update(held, now).total_N);
    ASSERT_TRUE(needle.forces().inside);
  }
  double largest_tick_jump = 0.0, largest_period_change = 0.0, lo = 1e9, hi = -1e9;
  for (std::size_t k = 1; k < force.size(); ++k)
    largest_tick_jump = std::max(largest_tick_jump, (force[k] - force[k - 1]).norm());
  for (std::size_t k = 20; k < force.size(); ++k)
    largest_period_change = std::max(largest_period_change, (force[k] - force[k - 20]).norm());
  for (const Eigen::Vector3d& f : force) {
    lo = std::min(lo, f.dot(D));
    hi = std::max(hi, f.dot(D));
  }
  // Felt: the breath moves the force by a tenth of a newton or more.
  EXPECT_GT((hi - lo), 0.1) << lo << " " << hi;
  // Continuous: no tick carries a physics update's whole change; it is spread over the period.
  EXPECT_GT(largest_period_change, 0.0);
  EXPECT_LT(largest_tick_jump, 0.2 * largest_period_change) << largest_tick_jump << " " << largest_period_change;
  EXPECT_LT(largest_tick_jump, 0.01);
  RecordProperty("breath_force_range_N", std::to_string(hi - lo));
  RecordProperty("largest_tick_jump_N", std::to_string(largest_tick_jump));
  RecordProperty("largest_20ms_change_N", std::to_string(largest_period_change));
}

TEST(NeedleHapticsTest, BreathingAlongAShallowNeedleIsContinuous) {
  // The needle just through the capsule (subcostal, so breathing moves the liver along it), held
  // while the liver breathes: the capsule's depth goes back and forth through the puncture depth
  // (where eq. 14 hands over to the withdrawal line) and the force follows without a jump.
  BreathingPatient patient(Patient().model);
  NeedleHaptics needle(Patient().ct);
  double t = 0.0;
  const Eigen::Vector3d D = (needle_test::TumourCentre() - needle_test::kSubcostalStart).normalized();
  double s = 0.0;
  while (needle.forces().capsule != CapsuleContact::kPunctured && s < 0.15)
    needle.Update({needle_test::kSubcostalStart + (s += 0.0002) * D, D}, t += 0.001);
  ASSERT_EQ(needle.forces().capsule, CapsuleContact::kPunctured);
  s += 0.002;  // 12 mm past the capsule
  const NeedlePose held{needle_test::kSubcostalStart + s * D, D};
  needle.Update(held, t += 0.001);
  const double depth0 = needle.forces().capsule_depth_m;
  double largest_tick = 0.0, shallowest = 1.0, deepest = 0.0;
  Eigen::Vector3d previous = needle.forces().total_N;
  for (int tick = 1; tick <= 4000; ++tick) {
    const double now = t + tick * 0.001;
    if (tick % 20 == 0) {
      patient.Update(tick * 0.001);
      needle.SetPatient(patient.snapshot(), now);
    }
    const NeedleForces& f = needle.Update(held, now);
    largest_tick = std::max(largest_tick, (f.total_N - previous).norm());
    previous = f.total_N;
    shallowest = std::min(shallowest, f.capsule == CapsuleContact::kNone ? 0.0 : f.capsule_depth_m);
    deepest = std::max(deepest, f.capsule_depth_m);
  }
  EXPECT_LT(shallowest, 0.010) << depth0;  // the liver moved along the needle, both ways
  EXPECT_GT(deepest, 0.010);
  EXPECT_LT(largest_tick, 0.02);
  RecordProperty("capsule_depth_range_mm", std::to_string(1e3 * shallowest) + " .. " + std::to_string(1e3 * deepest));
  RecordProperty("largest_tick_jump_N", std::to_string(largest_tick));
}

TEST(NeedleHapticsTest, BadPosesAreRefusedAndChangeNothing) {
  NeedleHaptics needle(Patient().ct), twin(Patient().ct);
  double t = 0.0, t2 = 0.0;
  const Eigen::Vector3d D = needle_test::kAnteriorDirection;
  Insert(needle, needle_test::kAnteriorStart, D, 0.06, t, 0.0005);
  Insert(twin, needle_test::kAnteriorStart, D, 0.06, t2, 0.0005);
  const NeedleForces before = needle.forces();
  const Eigen::Vector3d tip = needle_test::kAnteriorStart + 0.06 * D;
  const struct {
    NeedlePose pose;
    const char* says;
  } bad[] = {{{Eigen::Vector3d(NAN, 0, 0), D}, "tip position is not finite"},
             {{tip, Eigen::Vector3d(0, NAN, 0)}, "direction is not finite"},
             {{tip, Eigen::Vector3d::Zero()}, "zero length"},
             {{tip, Eigen::Vector3d(0, 1e-12, 0)}, "zero length"}};
  for (const auto& b : bad) {
    try {
      needle.Update(b.pose, t + 0.001);
      FAIL() << b.says;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(b.says), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("needle haptics"), std::string::npos);
    }
    EXPECT_EQ(needle.forces().total_N, before.total_N);
    EXPECT_EQ(needle.forces().capsule, before.capsule);
  }
  EXPECT_THROW(needle.Update({tip, D}, NAN), std::invalid_argument);
  // Afterwards it goes on exactly as one that never saw the bad input.
  Insert(needle, tip, D, 0.02, t, 0.0005);
  Insert(twin, tip, D, 0.02, t2, 0.0005);
  EXPECT_EQ(needle.forces().total_N, twin.forces().total_N);
  EXPECT_EQ(needle.metrics().insertion_attempts, twin.metrics().insertion_attempts);
  EXPECT_EQ(needle.metrics().no_go_crossings, twin.metrics().no_go_crossings);
  NeedleHapticsParameters p;
  p.max_force_N = 0.0;
  EXPECT_THROW(NeedleHaptics(Patient().ct, p), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
