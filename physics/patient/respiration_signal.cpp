#include "physics/patient/respiration_signal.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vesica::physics {
namespace {

void Require(bool ok, const char* field, const char* range, double value) {
  if (!ok)
    throw std::invalid_argument(std::string("respiration setting ") + field + " must be " + range + ", got " +
                                std::to_string(value));
}

double SmoothStep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace

void ValidateRespirationSettings(const RespirationSettings& s) {
  Require(std::isfinite(s.frequency_Hz) && s.frequency_Hz > 0.0, "frequency_Hz", "> 0", s.frequency_Hz);
  Require(std::isfinite(s.tendon_amplitude_m) && s.tendon_amplitude_m >= 0.0, "tendon_amplitude_m", ">= 0",
          s.tendon_amplitude_m);
  Require(std::isfinite(s.thoracic_scale) && s.thoracic_scale >= 0.0, "thoracic_scale", ">= 0", s.thoracic_scale);
  Require(std::isfinite(s.hold_fade_s) && s.hold_fade_s > 0.0, "hold_fade_s", "> 0", s.hold_fade_s);
}

RespirationSignal::RespirationSignal(const RespirationSettings& settings)
    : frequency_Hz_(settings.frequency_Hz), hold_fade_s_(settings.hold_fade_s) {
  ValidateRespirationSettings(settings);
}

void RespirationSignal::SetFrequency(double t_s, double frequency_Hz) {
  Require(std::isfinite(frequency_Hz) && frequency_Hz > 0.0, "frequency_Hz", "> 0", frequency_Hz);
  phase_at_anchor_ = Phase_rad(t_s);
  anchor_t_ = t_s;
  frequency_Hz_ = frequency_Hz;
}

void RespirationSignal::SetHoldFade(double hold_fade_s) {
  Require(std::isfinite(hold_fade_s) && hold_fade_s > 0.0, "hold_fade_s", "> 0", hold_fade_s);
  hold_fade_s_ = hold_fade_s;
}

void RespirationSignal::Hold(double t_s) {
  if (holding_) return;
  fade_from_ = Envelope(t_s);
  fade_start_t_ = t_s;
  holding_ = true;
}

void RespirationSignal::Resume(double t_s) {
  if (!holding_) return;
  fade_from_ = Envelope(t_s);
  fade_start_t_ = t_s;
  holding_ = false;
}

double RespirationSignal::Phase_rad(double t_s) const {
  return phase_at_anchor_ + 2.0 * std::numbers::pi * frequency_Hz_ * (t_s - anchor_t_);
}

double RespirationSignal::Envelope(double t_s) const {
  const double target = holding_ ? 0.0 : 1.0;
  if (fade_from_ == target) return target;
  return fade_from_ + (target - fade_from_) * SmoothStep((t_s - fade_start_t_) / hold_fade_s_);
}

double RespirationSignal::Unit(double t_s) const {
  const double envelope = Envelope(t_s);
  return envelope == 0.0 ? 0.0 : envelope * std::sin(Phase_rad(t_s));
}

}  // namespace vesica::physics
