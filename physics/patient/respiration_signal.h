#pragma once
// The breathing signal M(t) = A sin(2 pi f t) (seed eq. 2) that drives the ribs (eqs. 10-11) and
// the diaphragm's tendon (eq. 12), with the end-tidal breath hold of seed section 4: on "hold" the
// amplitude fades to 0 (end tidal, the scanned position) and stays there; on "resume" it fades
// back. The fade is a smoothstep of duration hold_fade_s, so M and dM/dt stay continuous.
// Changing f keeps the phase continuous (the signal does not jump).

namespace vesica::physics {

struct RespirationSettings {
  double frequency_Hz = 0.25;        ///< f, breaths per second; > 0 (quiet breathing 0.2-0.3, hyperventilation ~0.6)
  double tendon_amplitude_m = 0.02;  ///< d_max of eq. 12 (seed: 2 cm); >= 0
  double thoracic_scale = 1.0;       ///< scales alpha_max and beta_max (Table 1) for thoracic breathing; >= 0
  double hold_fade_s = 1.0;          ///< breath-hold fade in and out; > 0
};

/// Throws std::invalid_argument naming the field when a setting is out of range.
void ValidateRespirationSettings(const RespirationSettings& settings);

class RespirationSignal {
 public:
  explicit RespirationSignal(const RespirationSettings& settings = {});

  /// Changes f keeping the phase continuous at time t (the current time).
  void SetFrequency(double t_s, double frequency_Hz);
  void SetHoldFade(double hold_fade_s);
  /// The patient breathes out to end tidal and holds from time t; no-op when already holding.
  void Hold(double t_s);
  /// Breathing resumes from time t; no-op when not holding.
  void Resume(double t_s);
  [[nodiscard]] bool holding() const { return holding_; }

  /// sin-part of M(t)/A: envelope(t) * sin(phase(t)), in [-1, 1]. A is each organ's amplitude.
  [[nodiscard]] double Unit(double t_s) const;
  [[nodiscard]] double Phase_rad(double t_s) const;
  [[nodiscard]] double Envelope(double t_s) const;

 private:
  double frequency_Hz_;
  double hold_fade_s_;
  double phase_at_anchor_ = 0.0;  // phase = phase_at_anchor_ + 2 pi f (t - anchor_t_)
  double anchor_t_ = 0.0;
  bool holding_ = false;
  double fade_start_t_ = 0.0;
  double fade_from_ = 1.0;  // envelope when the last fade began
};

}  // namespace vesica::physics
