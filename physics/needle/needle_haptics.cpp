#include "physics/needle/needle_haptics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {
namespace {

constexpr double kGripFade_m = 0.002;

double Smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace

void ValidateNeedleHapticsParameters(const NeedleHapticsParameters& p) {
  const auto require = [](bool ok, const char* field, const char* rule) {
    if (!ok) throw std::invalid_argument(std::string("needle haptics: ") + field + " must be " + rule);
  };
  const auto finite = [](double x) { return std::isfinite(x); };
  require(finite(p.axial_N_per_HU) && p.axial_N_per_HU >= 0, "axial_N_per_HU", ">= 0");
  require(finite(p.sample_step_m) && p.sample_step_m >= 0, "sample_step_m", ">= 0");
  require(finite(p.lateral_onset_m) && p.lateral_onset_m > 0, "lateral_onset_m", "> 0");
  require(finite(p.lateral_stiffness_N_per_m) && p.lateral_stiffness_N_per_m >= 0, "lateral_stiffness_N_per_m", ">= 0");
  ValidateCapsuleForceParameters(p.capsule);
  require(finite(p.grip_lateral_stiffness_N_per_m) && p.grip_lateral_stiffness_N_per_m >= 0,
          "grip_lateral_stiffness_N_per_m", ">= 0");
  require(finite(p.grip_axial_stiffness_N_per_m) && p.grip_axial_stiffness_N_per_m > 0, "grip_axial_stiffness_N_per_m",
          "> 0");
  require(finite(p.grip_slip_force_N) && p.grip_slip_force_N >= 0, "grip_slip_force_N", ">= 0");
  require(finite(p.max_force_N) && p.max_force_N > 0, "max_force_N", "> 0");
  require(finite(p.blend_s) && p.blend_s > 0, "blend_s", "> 0");
}

std::vector<Eigen::Vector3d> PushedCapsulePoints(const PatientSnapshot& snapshot) {
  std::vector<Eigen::Vector3d> points;
  for (int e : snapshot.capsule_pushed)
    if (e >= 0 && static_cast<std::size_t>(e) < snapshot.liver_m.size())
      points.push_back(snapshot.liver_m[static_cast<std::size_t>(e)]);
  return points;
}

NeedleHaptics::NeedleHaptics(std::shared_ptr<const DeformedCtModel> ct, const NeedleHapticsParameters& parameters,
                             double start_s)
    : parameters_(parameters), ct_(std::move(ct)) {
  ValidateNeedleHapticsParameters(parameters_);
  if (!std::isfinite(start_s)) throw std::invalid_argument("needle haptics: start_s must be finite");
  step_m_ = parameters_.sample_step_m > 0 ? parameters_.sample_step_m : 0.5 * ct_.model().min_spacing_m;
  metrics_.start_s = start_s;
  patient_time_s_ = start_s;
}

void NeedleHaptics::SetPatient(const PatientSnapshot& snapshot, double now_s) {
  if (!std::isfinite(now_s)) throw std::invalid_argument("needle haptics: SetPatient's time is not finite");
  ct_.SetBlend((now_s - patient_time_s_) / parameters_.blend_s);
  ct_.SetPatient(snapshot);  // the state blended now becomes the previous one
  patient_time_s_ = now_s;
}

void NeedleHaptics::Withdrawn() {
  inside_ = false;
  last_no_go_ = -1;
  push_ = {};
  forces_ = {};
}

void NeedleHaptics::CountNoGo(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const CtSample& at_to) {
  // Every no-go structure the tip entered since the last tick, walked at the sampling step so that
  // a fast hand cannot jump over a 4 mm bundle.
  const double length = (to - from).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / step_m_)));
  for (int k = 1; k <= steps; ++k) {
    const std::uint8_t l = k == steps ? at_to.label : ct_.Sample(from + (to - from) * (double(k) / steps)).label;
    const std::optional<NoGo> kind = NoGoOfLabel(l);
    const int now = kind ? static_cast<int>(*kind) : -1;
    if (now >= 0 && now != last_no_go_) ++metrics_.no_go_crossings[static_cast<std::size_t>(now)];
    last_no_go_ = now;
  }
}

double NeedleHaptics::HounsfieldCrossed(const Eigen::Vector3d& entry, const Eigen::Vector3d& direction,
                                        double length_m) const {
  // Samples at fixed places from the entry point (and the end), so the sum grows continuously as
  // the tip advances: sum |HU(k+1) - HU(k)|, the integral of |dHU/ds| on the sampled field.
  if (length_m <= 0.0) return 0.0;
  double crossed = 0.0;
  DeformedCt::SampleHint hint;  // neighbouring samples start each other's inversion
  double previous = ct_.Sample(entry, &hint).hu;
  const int whole = static_cast<int>(std::floor(length_m / step_m_));
  for (int k = 1; k <= whole; ++k) {
    const double hu = ct_.Sample(entry + (k * step_m_) * direction, &hint).hu;
    crossed += std::abs(hu - previous);
    previous = hu;
  }
  if (length_m > whole * step_m_) crossed += std::abs(ct_.Sample(entry + length_m * direction, &hint).hu - previous);
  return crossed;
}

const NeedleForces& NeedleHaptics::Update(const NeedlePose& pose, double now_s) {
  // Everything checked before anything changes.
  const Eigen::Vector3d D = ValidatedDirection(pose, "needle haptics");
  if (!std::isfinite(now_s)) throw std::invalid_argument("needle haptics: the tick's time is not finite");
  const Eigen::Vector3d& P = pose.tip_m;
  const NeedleHapticsParameters& p = parameters_;

  ct_.SetBlend((now_s - patient_time_s_) / p.blend_s);
  const CtSample tip = ct_.Sample(P);
  const bool was_inside = inside_;
  // Seed 5.2: never a force outside the body. A share under 1e-9 is rounding in the voxel index
  // (a tip on a voxel's centre plane), not tissue.
  if (!(tip.body_fraction > 1e-9)) {
    Withdrawn();
    forces_.tip_label = tip.label;
    last_tip_ = P;
    any_pose_ = true;
    return forces_;
  }
  if (!was_inside) {  // an entry into the skin: a new insertion attempt
    inside_ = true;
    ++metrics_.insertion_attempts;
    p0_ = P;
    d0_ = D;
    forces_ = {};
    last_no_go_ = -1;
    CountNoGo(P, P, tip);
  } else {
    CountNoGo(last_tip_, P, tip);
  }
  last_tip_ = P;
  any_pose_ = true;

  NeedleForces f;
  f.inside = true;
  f.tip_label = tip.label;
  f.capsule = forces_.capsule;

  // The capsule (eq. 14) and the liver's hole.
  const double puncture = p.capsule.puncture_depth_m;
  if (f.capsule == CapsuleContact::kNone && tip.liver_occupancy >= 0.5) {
    f.capsule = CapsuleContact::kPushing;  // first touch: d = 0 here
    contact_rest_m_ = ct_.LiverRestPoint(P);
  }
  if (f.capsule != CapsuleContact::kNone) {
    f.capsule_contact_m = ct_.LiverWorldPoint(contact_rest_m_);
    f.capsule_depth_m = (P - f.capsule_contact_m).dot(D);
    if (f.capsule_depth_m < 0.0) {
      f.capsule = CapsuleContact::kNone;  // backed out of the capsule or the liver
      f.capsule_depth_m = 0.0;
    } else if (f.capsule == CapsuleContact::kPushing && f.capsule_depth_m >= puncture) {
      f.capsule = CapsuleContact::kPunctured;  // the hole holds the needle where it is now
      grip_stick_m_ = (f.capsule_contact_m - P).dot(D);
    }
  }
  if (f.capsule != CapsuleContact::kNone) {
    f.capsule_force_N = CapsuleForce_N(p.capsule, f.capsule_depth_m, f.capsule == CapsuleContact::kPunctured);
    f.capsule_N = -f.capsule_force_N * D;
  }
  push_ = {};
  if (f.capsule == CapsuleContact::kPushing) push_ = {true, f.capsule_contact_m, P - f.capsule_contact_m};
  if (f.capsule == CapsuleContact::kPunctured) {
    const Eigen::Vector3d r = f.capsule_contact_m - P;  // the hole, from the tip
    const double along = r.dot(D);
    double axial = p.grip_axial_stiffness_N_per_m * (along - grip_stick_m_);
    if (std::abs(axial) > p.grip_slip_force_N) {  // slips: the stick point follows
      axial = std::copysign(p.grip_slip_force_N, axial);
      grip_stick_m_ = along - axial / p.grip_axial_stiffness_N_per_m;
    }
    // The hole lets go as the tip draws back through it (over the last 2 mm): no jump on leaving.
    f.grip_N =
        Smoothstep(f.capsule_depth_m / kGripFade_m) * (axial * D + p.grip_lateral_stiffness_N_per_m * (r - along * D));
  }

  // Axial: the Hounsfield variation along the inserted needle, from the entry (P0 projected on the
  // needle's line) to the tip, or to the capsule while it is pushed ahead of the tip.
  const double inserted_length = (P - p0_).dot(D);
  double integrate_to = inserted_length;
  if (f.capsule == CapsuleContact::kPushing) integrate_to = std::max(0.0, inserted_length - f.capsule_depth_m);
  f.hu_crossed = HounsfieldCrossed(P - inserted_length * D, D, integrate_to);
  f.axial_N = -p.axial_N_per_HU * f.hu_crossed * D;

  // Lateral: back to the initial insertion line, growing in over the first millimetres.
  const Eigen::Vector3d from_p0 = P - p0_;
  f.inserted_m = from_p0.dot(d0_);
  const Eigen::Vector3d deviation = from_p0 - f.inserted_m * d0_;
  f.deviation_m = deviation.norm();
  f.lateral_N = -p.lateral_stiffness_N_per_m * Smoothstep(f.inserted_m / p.lateral_onset_m) * deviation;

  f.total_N = f.axial_N + f.lateral_N + f.capsule_N + f.grip_N;
  const double magnitude = f.total_N.norm();
  if (magnitude > p.max_force_N) {
    f.total_N *= p.max_force_N / magnitude;
    f.clamped = true;
  }
  forces_ = f;
  return forces_;
}

BiopsySample NeedleHaptics::TakeBiopsy(double now_s) {
  if (!std::isfinite(now_s)) throw std::invalid_argument("needle haptics: the biopsy's time is not finite");
  BiopsySample s;
  s.time_s = now_s;
  s.site_m = last_tip_;
  s.tumour_centre_m = ct_.TumourCentre_m();
  s.distance_m = (s.site_m - s.tumour_centre_m).norm();
  s.inside_body = inside_ && any_pose_;
  s.precision = s.inside_body ? PrecisionOfDistance(s.distance_m) : BiopsyPrecision::kNotPathologic;
  if (!metrics_.sample) metrics_.sample = s;
  return s;
}

}  // namespace vesica::physics
