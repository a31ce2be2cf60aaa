#include "physics/patient/breathing_patient.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

BreathingPatient::BreathingPatient(std::shared_ptr<const BreathingPatientModel> model)
    : model_(std::move(model)), settings_(model_->parameters.respiration), signal_(settings_) {
  if (!model_) throw std::invalid_argument("BreathingPatient: no model");
  u_diaphragm_.assign(static_cast<std::size_t>(model_->diaphragm.lattice.size()), Eigen::Vector3d::Zero());
  u_liver_.assign(static_cast<std::size_t>(model_->liver.lattice.size()), Eigen::Vector3d::Zero());
  Update(0.0);
  Publish();
}

void BreathingPatient::SetRespiration(const RespirationSettings& settings) {
  ValidateRespirationSettings(settings);
  const std::lock_guard lock(commands_mutex_);
  commands_.settings = settings;
}

void BreathingPatient::HoldBreath() {
  const std::lock_guard lock(commands_mutex_);
  commands_.hold = true;
}

void BreathingPatient::ResumeBreathing() {
  const std::lock_guard lock(commands_mutex_);
  commands_.hold = false;
}

void BreathingPatient::PushCapsule(const Eigen::Vector3d& tip_m, const Eigen::Vector3d& displacement_m) {
  if (!tip_m.allFinite() || !displacement_m.allFinite())
    throw std::invalid_argument("capsule push: the tip and its displacement must be finite");
  const std::lock_guard lock(commands_mutex_);
  commands_.push = std::make_pair(tip_m, displacement_m);
  commands_.release = false;
}

void BreathingPatient::ReleaseCapsule() {
  const std::lock_guard lock(commands_mutex_);
  commands_.push.reset();
  commands_.release = true;
}

void BreathingPatient::TakeCommands(double t_s) {
  Commands taken;
  {
    const std::lock_guard lock(commands_mutex_);
    std::swap(taken, commands_);
  }
  if (taken.settings) {
    if (taken.settings->frequency_Hz != settings_.frequency_Hz) signal_.SetFrequency(t_s, taken.settings->frequency_Hz);
    signal_.SetHoldFade(taken.settings->hold_fade_s);
    settings_ = *taken.settings;
  }
  if (taken.hold) {
    if (*taken.hold)
      signal_.Hold(t_s);
    else
      signal_.Resume(t_s);
  }
  if (taken.release) push_.reset();
  if (taken.push) push_ = taken.push;
}

void BreathingPatient::MoveDiaphragm(double tendon_m) {
  const DiaphragmModel& d = model_->diaphragm;
  std::fill(u_diaphragm_.begin(), u_diaphragm_.end(), Eigen::Vector3d::Zero());
  // Eq. 12: the central tendon translates rigidly along the body axis; inspiration (T > 0) is caudal.
  targets_.assign(d.tendon.size(), Eigen::Vector3d(0.0, 0.0, -tendon_m));
  const ChainMail::MoveReport report = d.mail->Move(d.tendon, targets_, u_diaphragm_);
  snapshot_.blocked += report.blocked;
}

void BreathingPatient::MoveLiver() {
  const LiverModel& liver = model_->liver;
  const BreathingPatientParameters& p = model_->parameters;
  std::fill(u_liver_.begin(), u_liver_.end(), Eigen::Vector3d::Zero());
  // Each coupled element sits where its coupling spring (to the diaphragm above it) balances the
  // liver's support: k_c (u_dia - u) = k_s u.
  const double share =
      p.coupling_stiffness_N_per_m / (p.coupling_stiffness_N_per_m + p.liver_support_stiffness_N_per_m);
  drivers_.clear();
  targets_.clear();
  for (const LiverCoupling& c : liver.coupling) {
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    for (std::size_t a = 0; a < c.diaphragm_elements.size(); ++a)
      anchor += static_cast<double>(c.weights[a]) * u_diaphragm_[static_cast<std::size_t>(c.diaphragm_elements[a])];
    drivers_.push_back(c.liver_element);
    targets_.push_back(share * anchor);
  }
  const ChainMail::MoveReport report = liver.mail->Move(drivers_, targets_, u_liver_, ChainMail::Drivers::kAtLeast);
  snapshot_.blocked += report.blocked;
  LiverLiftsDiaphragm();
  KeepLiverUnderDiaphragm();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < drivers_.size(); ++i)
    force += p.coupling_stiffness_N_per_m * (targets_[i] / share - u_liver_[static_cast<std::size_t>(drivers_[i])]);
  snapshot_.coupling_force_N = force;
}

void BreathingPatient::LiverLiftsDiaphragm() {
  // The diaphragm's muscle is passive (seed 4.4): where the liver, pulled up by the tendon, rises
  // more than the muscle over it, it lifts the muscle. A lift the fixed crura would refuse is not
  // made; then KeepLiverUnderDiaphragm holds the liver down instead.
  const LiverModel& liver = model_->liver;
  const DiaphragmModel& dia = model_->diaphragm;
  const double tendon_z = u_diaphragm_[static_cast<std::size_t>(dia.tendon.front())].z();
  lift_.assign(u_diaphragm_.size(), -INFINITY);
  bool any = false;
  for (int e = 0; e < liver.lattice.size(); ++e) {
    const auto ue = static_cast<std::size_t>(e);
    for (int q = liver.under_first[ue]; q < liver.under_first[ue + 1]; ++q) {
      const auto d = static_cast<std::size_t>(liver.under_diaphragm[static_cast<std::size_t>(q)]);
      const double most = std::min(dia.rise_over_crura_m[d], tendon_z + dia.rise_over_tendon_m[d]) - 1e-9;
      const double need = std::min(most, u_liver_[ue].z() - liver.under_allowance_m[static_cast<std::size_t>(q)]);
      if (need > u_diaphragm_[d].z() && need > lift_[d]) {
        lift_[d] = need;
        any = true;
      }
    }
  }
  if (!any) return;
  cap_drivers_.clear();
  cap_targets_.clear();
  for (std::size_t d = 0; d < lift_.size(); ++d)
    if (lift_[d] > -INFINITY) {
      cap_drivers_.push_back(static_cast<int>(d));
      cap_targets_.emplace_back(u_diaphragm_[d].x(), u_diaphragm_[d].y(), lift_[d]);
    }
  snapshot_.blocked +=
      dia.mail->Move(cap_drivers_, cap_targets_, u_diaphragm_, ChainMail::Drivers::kAtLeast, dia.held).blocked;
}

void BreathingPatient::KeepLiverUnderDiaphragm() {
  // Where the liver's mail carried an element higher than the diaphragm above it allows (under
  // the muscular part, which rises less than the tendon), it is held there and the mail follows.
  const LiverModel& liver = model_->liver;
  std::vector<int>& capped = cap_drivers_;
  std::vector<Eigen::Vector3d>& caps = cap_targets_;
  capped.clear();
  caps.clear();
  for (int e = 0; e < liver.lattice.size(); ++e) {
    const auto ue = static_cast<std::size_t>(e);
    double cap = INFINITY;
    for (int q = liver.under_first[ue]; q < liver.under_first[ue + 1]; ++q)
      cap =
          std::min(cap, u_diaphragm_[static_cast<std::size_t>(liver.under_diaphragm[static_cast<std::size_t>(q)])].z() +
                            liver.under_allowance_m[static_cast<std::size_t>(q)]);
    if (u_liver_[ue].z() > cap) {
      capped.push_back(e);
      caps.emplace_back(u_liver_[ue].x(), u_liver_[ue].y(), cap);
    }
  }
  if (!capped.empty())
    snapshot_.blocked += liver.mail->Move(capped, caps, u_liver_, ChainMail::Drivers::kAtLeast).blocked;
}

void BreathingPatient::PushLiverCapsule() {
  std::fill(std::begin(snapshot_.capsule_pushed), std::end(snapshot_.capsule_pushed), -1);
  if (!push_) return;
  const LiverModel& liver = model_->liver;
  const auto& [tip, displacement] = *push_;
  // The three capsule elements nearest the tip, where they are now.
  std::pair<double, int> nearest[3] = {{INFINITY, -1}, {INFINITY, -1}, {INFINITY, -1}};
  for (int e : liver.capsule) {
    const auto ue = static_cast<std::size_t>(e);
    const double d2 = (liver.lattice.rest_m[ue] + u_liver_[ue] - tip).squaredNorm();
    if (d2 < nearest[2].first) {
      nearest[2] = {d2, e};
      std::sort(std::begin(nearest), std::end(nearest));
    }
  }
  drivers_.clear();
  targets_.clear();
  for (int n = 0; n < 3; ++n) {
    if (nearest[n].second < 0) continue;
    snapshot_.capsule_pushed[n] = nearest[n].second;
    drivers_.push_back(nearest[n].second);
    targets_.push_back(u_liver_[static_cast<std::size_t>(nearest[n].second)] + displacement);
  }
  snapshot_.blocked += liver.mail->Move(drivers_, targets_, u_liver_).blocked;
}

void BreathingPatient::Update(double t_s) {
  TakeCommands(t_s);
  const BreathingPatientModel& m = *model_;
  snapshot_.time_s = t_s;
  snapshot_.blocked = 0;
  snapshot_.signal = signal_.Unit(t_s);
  snapshot_.holding = signal_.holding();
  double tendon = settings_.tendon_amplitude_m * snapshot_.signal;  // eq. 12
  const double limit = m.diaphragm.max_tendon_displacement_m;
  snapshot_.tendon_limited = std::abs(tendon) > limit;
  tendon = std::clamp(tendon, -limit * (1.0 - 1e-6), limit * (1.0 - 1e-6));  // float bounds: stay inside
  snapshot_.tendon_displacement_m = tendon;

  snapshot_.ribs.resize(m.ribs.size());
  for (std::size_t r = 0; r < m.ribs.size(); ++r)
    snapshot_.ribs[r] = PoseRib(m.ribs[r], snapshot_.signal, settings_.thoracic_scale);

  const auto place = [](const std::vector<Eigen::Vector3d>& rest, const std::vector<Eigen::Vector3d>& u,
                        std::vector<Eigen::Vector3d>& out) {
    out.resize(rest.size());
    for (std::size_t i = 0; i < rest.size(); ++i) out[i] = rest[i] + u[i];
  };
  MoveDiaphragm(tendon);
  if (liver_motion_) {
    u_liver_ = liver_motion_(t_s);
    if (u_liver_.size() != m.liver.lattice.rest_m.size())
      throw std::invalid_argument("BreathingPatient: the liver motion gave " + std::to_string(u_liver_.size()) +
                                  " displacements for " + std::to_string(m.liver.lattice.rest_m.size()) +
                                  " liver elements");
  } else {
    MoveLiver();
  }
  place(m.liver.lattice.rest_m, u_liver_, snapshot_.liver_breathing_m);
  PushLiverCapsule();

  place(m.diaphragm.lattice.rest_m, u_diaphragm_, snapshot_.diaphragm_m);
  place(m.liver.lattice.rest_m, u_liver_, snapshot_.liver_m);
  snapshot_.tumour_centre_m = m.liver.tumour_centre_m;
  if (m.liver.has_tumour) snapshot_.tumour_centre_m += m.liver.tumour.Displacement(0, u_liver_);
}

void BreathingPatient::Publish() {
  render_.Publish(snapshot_);
  haptic_.Publish(snapshot_);
}

}  // namespace vesica::physics
