#include "app/biopsy/biopsy_session.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::app::biopsy {
namespace {

bool CarriesTumourCells(physics::BiopsyPrecision precision) {
  return precision == physics::BiopsyPrecision::kGoodSpecimen ||
         precision == physics::BiopsyPrecision::kSomeTumourCells;
}

}  // namespace

void ValidateBiopsySessionSettings(const BiopsySessionSettings& settings) {
  physics::ValidateRespirationSettings(settings.respiration);
  physics::ValidateNeedleHapticsParameters(settings.needle);
  if (!(settings.patient_period_s > 0.0) || !std::isfinite(settings.patient_period_s))
    throw std::invalid_argument("biopsy session: patient_period_s must be > 0, got " +
                                std::to_string(settings.patient_period_s));
  if (!settings.place_stylus_at_tumour && !(settings.placement.scale > 0.0))
    throw std::invalid_argument("biopsy session: placement.scale must be > 0, got " +
                                std::to_string(settings.placement.scale));
}

BiopsySession::BiopsySession(std::shared_ptr<const BiopsyPatient> patient, BiopsySessionSettings settings)
    : patient_(patient ? std::move(patient) : throw std::invalid_argument("biopsy session: no patient")),
      settings_((ValidateBiopsySessionSettings(settings), std::move(settings))),
      breathing_(patient_->model),
      needle_(patient_->ct, settings_.needle, 0.0) {
  if (settings_.place_stylus_at_tumour)
    settings_.placement = PlacementAtRightSide(patient_->model->liver.tumour_centre_m);
  breathing_.SetRespiration(settings_.respiration);
  if (settings_.liver_motion) breathing_.DriveLiver(settings_.liver_motion);
  breathing_.Update(0.0);
  needle_.SetPatient(breathing_.snapshot(), 0.0);
  next_patient_update_s_ = settings_.patient_period_s;
}

const physics::NeedleForces& BiopsySession::Tick(const device::StylusState& stylus, double t_s) {
  if (!std::isfinite(t_s) || (ticked_ && t_s < time_s_))
    throw std::invalid_argument("biopsy session: tick time " + std::to_string(t_s) + " s is before the last (" +
                                std::to_string(time_s_) + " s) or not finite");
  if (const auto problem = device::StylusStateProblem(stylus))
    throw std::invalid_argument("biopsy session: stylus sample at " + std::to_string(t_s) + " s: " + *problem);
  const physics::NeedlePose pose = NeedleInWorld(settings_.placement, stylus);

  // The patient first, at its own fixed times, so the needle sees the same states in a replay.
  while (next_patient_update_s_ <= t_s) {
    breathing_.Update(next_patient_update_s_);
    breathing_.Publish();
    needle_.SetPatient(breathing_.snapshot(), next_patient_update_s_);
    next_patient_update_s_ += settings_.patient_period_s;
  }
  const physics::NeedleForces& forces = needle_.Update(pose, t_s);  // throws before any change
  pose_ = pose;
  time_s_ = t_s;
  ticked_ = true;

  const physics::CapsulePush push = needle_.capsule_push();
  if (push.active) {
    breathing_.PushCapsule(push.surface_m, push.displacement_m);
  } else {
    breathing_.ReleaseCapsule();
  }
  const bool button1 = (stylus.buttons & device::kStylusButton1) != 0;
  if (button1 && !button1_was_down_ && !finished()) needle_.TakeBiopsy(t_s);
  button1_was_down_ = button1;

  if (forces.inside) {
    const double magnitude = forces.total_N.norm();
    max_force_N_ = std::max(max_force_N_, magnitude);
    force_sum_N_ += magnitude;
    ++force_ticks_;
  }
  return forces;
}

Eigen::Vector3d BiopsySession::DeviceForce() const {
  return ForceOnDevice(settings_.placement, needle_.forces().total_N);
}

SessionMetrics BiopsySession::Metrics() const {
  const physics::BiopsyMetrics& m = needle_.metrics();
  SessionMetrics out;
  out.duration_s = m.time_to_sample_s().value_or(time_s_ - m.start_s);
  out.max_force_N = max_force_N_;
  out.mean_force_N = force_ticks_ > 0 ? force_sum_N_ / static_cast<double>(force_ticks_) : 0.0;
  out.nogo_crossings = m.total_no_go_crossings();
  out.insertion_attempts = m.insertion_attempts;
  if (m.sample) {
    out.biopsy_sampled = true;
    out.time_to_sample_s = *m.time_to_sample_s();
    out.sample_distance_m = m.sample->distance_m;
    out.success = CarriesTumourCells(m.sample->precision) && out.nogo_crossings == 0;
  }
  return out;
}

}  // namespace vesica::app::biopsy
